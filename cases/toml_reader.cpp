#include "sympathy/cases/toml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "sympathy/cases/names.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy {

void check_toml_shape(const std::string& text, const std::string& path) {
  // One pass outside strings and comments: the nesting of [ and {, and per key the dots between
  // delimiters (a number's one dot, or a date's, never comes near the limit).
  enum class In { Code, Basic, Literal, MultiBasic, MultiLiteral, Comment } in = In::Code;
  int line = 1, depth = 0, dots = 0;
  const auto fail = [&](const std::string& what) {
    throw InputError(path + ":" + std::to_string(line) + ": " + what);
  };
  const auto starts = [&](std::size_t i, const char* s) { return text.compare(i, 3, s) == 0; };
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      if (in == In::Comment) in = In::Code;
      if (in == In::Basic || in == In::Literal) in = In::Code;  // the parser will say why
      if (in == In::Code) dots = 0;
      continue;
    }
    switch (in) {
      case In::Comment:
        break;
      case In::Basic:
        if (c == '\\')
          ++i;
        else if (c == '"')
          in = In::Code;
        break;
      case In::Literal:
        if (c == '\'') in = In::Code;
        break;
      case In::MultiBasic:
        if (c == '\\')
          ++i;
        else if (starts(i, "\"\"\""))
          in = In::Code, i += 2;
        break;
      case In::MultiLiteral:
        if (starts(i, "'''")) in = In::Code, i += 2;
        break;
      case In::Code:
        if (c == '#') {
          in = In::Comment;
        } else if (starts(i, "\"\"\"")) {
          in = In::MultiBasic, i += 2;
        } else if (starts(i, "'''")) {
          in = In::MultiLiteral, i += 2;
        } else if (c == '"') {
          in = In::Basic;
        } else if (c == '\'') {
          in = In::Literal;
        } else if (c == '[' || c == '{') {
          if (++depth > kMaxTomlNesting)
            fail("brackets nested more than " + std::to_string(kMaxTomlNesting) +
                 " deep; expected at most " + std::to_string(kMaxTomlNesting));
          dots = 0;
        } else if (c == ']' || c == '}') {
          depth = std::max(depth - 1, 0);
          dots = 0;
        } else if (c == '=' || c == ',') {
          dots = 0;
        } else if (c == '.') {
          if (++dots >= kMaxTomlKeyParts)
            fail("a dotted key of more than " + std::to_string(kMaxTomlKeyParts) +
                 " parts; expected at most " + std::to_string(kMaxTomlKeyParts));
        }
        break;
    }
  }
}

toml::table parse_toml(const std::string& text, const std::string& path) {
  check_toml_shape(text, path);
  try {
    return toml::parse(text, path);
  } catch (const toml::parse_error& e) {
    throw InputError(path + ":" + std::to_string(e.source().begin.line) + ":" +
                     std::to_string(e.source().begin.column) +
                     ": not valid TOML: " + std::string(e.description()));
  }
}

toml::table read_toml(const std::string& path, const std::string& what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot read the " + what + " (a directory; expected a file)");
  if (!std::filesystem::is_regular_file(path, ec))
    throw InputError(path + ": cannot read the " + what + " (no such file)");
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(path + ": cannot read the " + what);
  return parse_toml(text.str(), path);
}

std::string TomlReader::where(int line) const {
  return path_ + ":" + std::to_string(line);
}

std::string TomlReader::where(const toml::node& node) const {
  return where(static_cast<int>(node.source().begin.line));
}

void TomlReader::fail(int line, const std::string& key, const std::string& expected,
                      const std::string& got) const {
  std::string msg = where(line) + ": key '" + key + "': expected " + expected;
  if (!got.empty()) msg += ", got " + got;
  throw InputError(msg);
}

void TomlReader::fail(const toml::node& node, const std::string& key,
                      const std::string& expected) const {
  fail(static_cast<int>(node.source().begin.line), key, expected, describe(node));
}

std::string TomlReader::describe(const toml::node& node) {
  if (node.is_string()) {
    std::string quoted = "\"";
    quoted += *node.value<std::string_view>();
    quoted += '"';
    return quoted;
  }
  if (node.is_number()) return format_number(*node.value<double>());
  if (node.is_boolean()) return *node.value<bool>() ? "true" : "false";
  if (node.is_table()) return "a table";
  if (node.is_array()) return "an array";
  return "a value of another type";
}

void TomlReader::only(const toml::table& table, const std::string& prefix,
                      const std::vector<std::string>& allowed) const {
  for (auto&& [key, node] : table) {
    const std::string k(key.str());
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
      fail(static_cast<int>(key.source().begin.line), prefix + k,
           "one of the keys " + join(allowed) + " (unknown key)");
  }
}

double TomlReader::number(const toml::node& node, const std::string& key) const {
  if (!node.is_number()) fail(node, key, "a number");
  const double v = *node.value<double>();
  if (!std::isfinite(v)) fail(node, key, "a finite number");
  return v;
}

int TomlReader::integer(const toml::node& node, const std::string& key) const {
  if (!node.is_integer()) fail(node, key, "an integer");
  // TOML integers are 64-bit; narrowed, 4294967297 would become 1 and be refused (or taken) as
  // something the file never said.
  const int64_t v = *node.value<int64_t>();
  if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
    fail(node.source().begin.line, key,
         "an integer between " + std::to_string(std::numeric_limits<int>::min()) + " and " +
             std::to_string(std::numeric_limits<int>::max()),
         std::to_string(v));
  return static_cast<int>(v);
}

const toml::table& TomlReader::table(const toml::node& node, const std::string& key) const {
  if (!node.is_table()) fail(node, key, "a table");
  return *node.as_table();
}

std::string TomlReader::string(const toml::node& node, const std::string& key) const {
  if (!node.is_string()) fail(node, key, "a string");
  return std::string(*node.value<std::string_view>());
}

}  // namespace sympathy
