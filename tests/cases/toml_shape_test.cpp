// The limits on a TOML text's shape checked before the parser sees it (toml_reader.hpp): a
// table header of 50,000 dotted parts overflowed toml++'s recursion (issue 32: SIGSEGV in every
// reader and in Python). The limits must refuse such a text with the line, and must not count
// what is inside strings or comments, nor a number's dot.
#include "sympathy/cases/toml_reader.hpp"

#include <string>

#include <gtest/gtest.h>

#include "sympathy/core/errors.hpp"
#include "tests/support/errors.hpp"

namespace sympathy {
namespace {

std::string parts(int n) {
  std::string key = "a";
  for (int i = 1; i < n; ++i) key += ".a";
  return key;
}

std::string error_of(const std::string& text) {
  return testing::input_error_of([&] { parse_toml(text, "f.toml"); });
}

TEST(TomlShape, DottedKeysAreLimitedBeforeParsing) {
  EXPECT_NO_THROW(parse_toml("x = 1\n[" + parts(kMaxTomlKeyParts) + "]\ny = 2\n", "f.toml"));
  EXPECT_NO_THROW(parse_toml(parts(kMaxTomlKeyParts) + " = 1\n", "f.toml"));
  EXPECT_EQ(error_of("x = 1\n[" + parts(kMaxTomlKeyParts + 1) + "]\n"),
            "f.toml:2: a dotted key of more than 64 parts; expected at most 64");
  EXPECT_EQ(error_of("\n\n" + parts(50000) + " = 1\n"),
            "f.toml:3: a dotted key of more than 64 parts; expected at most 64");
  EXPECT_EQ(error_of("[" + parts(50000) + "]\n"),
            "f.toml:1: a dotted key of more than 64 parts; expected at most 64");
  // Inline tables' keys count too.
  EXPECT_EQ(error_of("t = {" + parts(100) + " = 1}\n"),
            "f.toml:1: a dotted key of more than 64 parts; expected at most 64");
}

TEST(TomlShape, NestingIsLimitedBeforeParsing) {
  const auto nested = [](int n, char open, char close) {
    return "x = " + std::string(n, open) + std::string(n, close) + "\n";
  };
  EXPECT_NO_THROW(parse_toml(nested(kMaxTomlNesting, '[', ']'), "f.toml"));
  EXPECT_EQ(error_of("y = 0\n" + nested(kMaxTomlNesting + 1, '[', ']')),
            "f.toml:2: brackets nested more than 64 deep; expected at most 64");
  EXPECT_EQ(error_of(nested(100000, '[', ']')),
            "f.toml:1: brackets nested more than 64 deep; expected at most 64");
  std::string inline_tables = "x = ";
  for (int i = 0; i < 100; ++i) inline_tables += "{a = ";
  inline_tables += "1" + std::string(100, '}') + "\n";
  EXPECT_EQ(error_of(inline_tables),
            "f.toml:1: brackets nested more than 64 deep; expected at most 64");
}

// What is not a key or a bracket is not counted: dots and brackets in strings of every kind and
// in comments, numbers' and dates' dots, many keys of one part each.
TEST(TomlShape, StringsCommentsAndNumbersAreNotCounted) {
  const std::string many_dots(1000, '.'), many_brackets(1000, '[');
  const std::string text = "a = \"" + many_dots + many_brackets + "\"\nb = '" + many_dots +
                           many_brackets + "'\nc = \"\"\"\n" + many_dots + "\n" + many_brackets +
                           "\n\"\"\"\nd = '''\n" + many_dots + many_brackets + "'''\n# " +
                           many_dots + many_brackets + "\ne = 1.5\nf = 1979-05-27T07:32:00.999\n" +
                           "g = \"esc\\\" " + many_dots + "\"\n";
  const auto table = parse_toml(text, "f.toml");
  EXPECT_EQ(table["a"].value<std::string>()->size(), 2000u);
  EXPECT_EQ(*table["e"].value<double>(), 1.5);
  std::string wide;
  for (int i = 0; i < 1000; ++i) {
    const std::string n = std::to_string(i);
    wide.append("k").append(n).append(" = ").append(n).append(".5\n");
  }
  EXPECT_NO_THROW(parse_toml(wide, "f.toml"));
}

}  // namespace
}  // namespace sympathy
