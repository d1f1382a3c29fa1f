// The one option table (cases/app/option_table.hpp): every command's options have a kind, unique
// names and Python keywords; the command line reads each value by its kind when it is given, and
// values given typed (Python's) are taken as they are.
#include "cases/app/option_table.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "cases/app/arguments.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy {
namespace {

using app::OptionKind;

const app::OptionSpec& find(const std::vector<app::OptionSpec>& options, const std::string& name) {
  const auto it = std::find_if(options.begin(), options.end(),
                               [&](const app::OptionSpec& s) { return s.name == name; });
  EXPECT_NE(it, options.end()) << name;
  return *it;
}

TEST(OptionTable, EveryOptionHasAKindAUniqueNameAndAPythonKeyword) {
  // Python's reserved words an option's keyword must not be (from_ is --from's).
  const std::set<std::string> reserved = {"from",   "import", "in",    "is",  "lambda",
                                          "global", "pass",   "class", "def", "for",
                                          "if",     "or",     "and"};
  for (const auto& command : app::commands()) {
    const auto table = app::command_options(command);
    std::set<std::string> names, keywords;
    for (const auto& s : table.options) {
      EXPECT_NO_THROW(app::kind_of(s)) << command << " " << s.name;
      EXPECT_TRUE(names.insert(s.name).second) << command << ": " << s.name << " twice";
      const std::string k = app::keyword_of(s.name);
      EXPECT_TRUE(keywords.insert(k).second) << command << ": keyword " << k << " twice";
      EXPECT_EQ(reserved.count(k), 0u) << k;
      for (char c : k) EXPECT_TRUE(std::isalnum(static_cast<unsigned char>(c)) || c == '_') << k;
      if (app::kind_of(s) == OptionKind::Choice) {
        EXPECT_GE(app::choices_of(s).size(), 2u);
      }
    }
  }
  EXPECT_THROW(app::command_options("contineu"), InputError);
}

TEST(OptionTable, KindsReadFromThePlaceholders) {
  const auto c = app::continue_options();
  EXPECT_EQ(app::kind_of(find(c, "--max-points")), OptionKind::Integer);
  EXPECT_EQ(app::kind_of(find(c, "--from")), OptionKind::Number);
  EXPECT_EQ(app::kind_of(find(c, "--user-points")), OptionKind::Numbers);
  EXPECT_EQ(app::kind_of(find(c, "--set")), OptionKind::Assignments);
  EXPECT_EQ(app::kind_of(find(c, "--param")), OptionKind::Text);
  EXPECT_EQ(app::kind_of(find(c, "--quiet")), OptionKind::Flag);
  EXPECT_EQ(app::choices_of(find(c, "--method")),
            (std::vector<std::string>{"bdf", "adams", "erk"}));
  EXPECT_EQ(app::kind_of(find(app::fit_options(), "--free")), OptionKind::Names);
  EXPECT_THROW(app::kind_of({"--odd", "WHAT", false, "", false}), std::logic_error);
}

TEST(OptionTable, MessagesNameKeywordsForPython) {
  const auto fit = app::fit_options();
  EXPECT_EQ(app::with_keywords("--max-evaluations 0: expected a positive integer", fit),
            "max_evaluations 0: expected a positive integer");
  // The longer name is not taken for the shorter one's.
  EXPECT_EQ(app::with_keywords("--free-initial th1 with --free d", fit),
            "free_initial th1 with free d");
  EXPECT_EQ(app::with_keywords("--from 2 above --to 1", app::continue_options()),
            "from_ 2 above to 1");
}

TEST(Arguments, ValuesAreReadByTheirKindWhenGiven) {
  const auto options = app::continue_options();
  const auto message = [&](std::vector<std::string> argv) {
    try {
      app::Arguments("continue", argv, options, {"CASE"});
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::vector<std::string> window = {"c.toml", "--param", "k", "--from", "1", "--to", "2"};
  auto with = [&](std::vector<std::string> more) {
    auto a = window;
    a.insert(a.end(), more.begin(), more.end());
    return a;
  };
  EXPECT_EQ(message(window), "accepted");
  EXPECT_EQ(message(with({"--max-points", "1.5"})), "--max-points 1.5: expected an integer");
  EXPECT_EQ(message(with({"--step", "x"})), "--step x: expected a finite number");
  EXPECT_EQ(message(with({"--method", "rk4"})), "--method rk4: expected bdf, adams or erk");
  EXPECT_EQ(message(with({"--set", "k"})).find("--set"), 0u);
  EXPECT_EQ(message(with({"--step", "1", "--step", "2"})),
            "--step: given twice; expected it at most once");
  const app::Arguments args("continue", with({"--user-points", "30,60", "--set", "c=0.5"}), options,
                            {"CASE"});
  EXPECT_EQ(args.numbers("--user-points"), (std::vector<double>{30, 60}));
  EXPECT_EQ(args.assignments("--set").at(0).value, 0.5);
}

// Typed values (Python's keywords) are taken as given: 0.1 + 0.2 stays 0.30000000000000004, an
// integer stays one; the checks of repetition, choices and required options are the same.
TEST(Arguments, TypedValuesAreTakenAsTheyAre) {
  const auto options = app::continue_options();
  const auto given = [](std::string name, std::optional<double> number,
                        std::optional<int> integer = std::nullopt, std::string text = "") {
    app::GivenOption g;
    g.name = std::move(name);
    g.number = number;
    g.integer = integer;
    g.text = std::move(text);
    return g;
  };
  const double from = 0.1 + 0.2;
  const app::Arguments args(
      "continue", {"c.toml"},
      {given("--param", std::nullopt, std::nullopt, "k"), given("--from", from), given("--to", 2.0),
       given("--max-points", std::nullopt, 7)},
      options, {"CASE"});
  EXPECT_EQ(args.number("--from", 0.0), from);
  EXPECT_EQ(args.integer("--max-points", 0), 7);
  EXPECT_THROW(
      app::Arguments("continue", {"c.toml"},
                     {given("--param", std::nullopt, std::nullopt, "k"), given("--from", 1.0)},
                     options, {"CASE"}),
      InputError);  // --to missing
  EXPECT_THROW(
      app::Arguments("continue", {"c.toml"},
                     {given("--param", std::nullopt, std::nullopt, "k"), given("--from", 1.0),
                      given("--to", 2.0), given("--method", std::nullopt, std::nullopt, "rk4")},
                     options, {"CASE"}),
      InputError);
}

}  // namespace
}  // namespace sympathy
