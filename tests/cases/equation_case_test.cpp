// Equation case files (cases/equation_case.hpp): the examples load; every class of bad file is
// refused with a message naming the file, line, column (where there is one) and what was
// expected; code smuggled through names, expressions and comments is refused before anything
// is generated.
#include "sympathy/cases/equation_case.hpp"

#include <string>

#include <gtest/gtest.h>

#include "tests/support/cases.hpp"
#include "tests/support/errors.hpp"

namespace sympathy {
namespace {

using testing::input_error_of;
using testing::write_test_file;

using testing::example_path;

// A small valid file; tests replace one piece of it.
const std::string kValid = R"(kind = "equations"
[states]
x = 1.0
y = 0.0
[parameters]
a = 0.5
b = { value = 2.0, unit = "1/s", min = 0.0, max = 10.0 }
[intermediates]
r2 = "x^2 + y^2"
[equations]
x = "a*x - b*y - x*r2"
y = "b*x + a*y - y*r2"
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

// The message of loading `text` as a file.
std::string error_of_file(const std::string& text) {
  const std::string path = write_test_file("sympathy_equation_case_test", ".toml", text);
  return input_error_of([&] { EquationCase::load(path); });
}

void expect_contains(const std::string& message, const std::string& part) {
  EXPECT_NE(message.find(part), std::string::npos)
      << "message: " << message << "\nexpected to contain: " << part;
}

// [steep]: per state, a width (and optionally a scale) from the parameters alone, positive at
// the file's values; each wrong entry refused where it stands.
TEST(EquationCase, SteepZones) {
  const auto c = EquationCase::load(
      write_test_file("sympathy_equation_case_test", ".toml",
                      kValid + "[steep]\ny = \"a/50\"\nx = { width = \"b*pi\", scale = \"2\" }\n"));
  ASSERT_EQ(c.system().steep.size(), 2u);
  EXPECT_EQ(c.system().steep[0].state, 0);  // in state order, not the file's
  EXPECT_TRUE(c.system().steep[0].scale.has_value());
  EXPECT_EQ(c.system().steep[1].state, 1);
  EXPECT_FALSE(c.system().steep[1].scale.has_value());
  expect_contains(error_of_file(kValid + "[steep]\ny = \"x/50\"\n"),
                  ".toml:14:6: key 'steep.y': expected parameters, numbers and pi only (a zone's "
                  "size does not change along the motion), got 'x'");
  expect_contains(error_of_file(kValid + "[steep]\nr2 = \"a\"\n"),
                  ".toml:14:1: key 'steep.r2': expected a state of [states] (x, y), got 'r2', not "
                  "a state");
  expect_contains(error_of_file(kValid + "[steep]\ny = \"a - 1\"\n"),
                  ".toml:14: key 'steep.y': expected a positive value at the file's parameter "
                  "values, got -0.5");
  expect_contains(error_of_file(kValid + "[steep]\ny = { scale = \"1\" }\n"),
                  "key 'steep.y.width' is missing: expected the zone's half-width");
}

// [[impacts]]: a surface (an expression of states, parameters, intermediates and t), a direction
// ("decreasing" by default) and the states after the impact, in state order; each wrong entry
// refused where it stands.
TEST(EquationCase, Impacts) {
  const auto c = EquationCase::load(write_test_file(
      "sympathy_equation_case_test", ".toml",
      kValid + "[[impacts]]\nsurface = \"x - a\"\nreset = { y = \"-b*y\", x = \"a\" }\n"
               "[[impacts]]\nsurface = \"r2 - 4\"\ndirection = \"increasing\"\n"
               "reset = { y = \"0\" }\n"));
  ASSERT_EQ(c.system().impacts.size(), 2u);
  EXPECT_EQ(c.system().impacts[0].direction, -1);
  ASSERT_EQ(c.system().impacts[0].reset.size(), 2u);
  EXPECT_EQ(c.system().impacts[0].reset[0].first, 0);  // in state order, not the file's
  EXPECT_EQ(c.system().impacts[0].reset[1].first, 1);
  EXPECT_EQ(c.system().impacts[1].direction, 1);
  expect_contains(error_of_file(kValid + "[[impacts]]\nreset = { y = \"0\" }\n"),
                  ".toml:13: key 'impacts[1].surface' is missing: expected the impact surface h");
  expect_contains(
      error_of_file(kValid + "[[impacts]]\nsurface = \"x\"\ndirection = \"down\"\n"
                             "reset = { y = \"0\" }\n"),
      ".toml:15: key 'impacts[1].direction': expected \"decreasing\" (the impact where h falls "
      "through 0, from h > 0) or \"increasing\"");
  expect_contains(error_of_file(kValid + "[[impacts]]\nsurface = \"x\"\n"),
                  "key 'impacts[1].reset' is missing: expected the states after the impact");
  expect_contains(
      error_of_file(kValid + "[[impacts]]\nsurface = \"x\"\nreset = { r2 = \"0\" }\n"),
      "key 'impacts[1].reset.r2': expected a state of [states] (x, y), got 'r2', not a state");
  expect_contains(
      error_of_file(kValid + "[[impacts]]\nsurface = \"x - q\"\nreset = { y = \"0\" }\n"),
      ".toml:14:16: key 'impacts[1].surface': expected a state, a parameter, an intermediate, t "
      "or pi");
  expect_contains(
      error_of_file(kValid + "[[impacts]]\nsurface = \"x\"\nspeed = 1\nreset = { y = \"0\" }\n"),
      "impacts[1].speed");
}

// plugin = "FILE.cpp": a C++ source beside the case file instead of equations; a file that also
// has equations, or names no .cpp file that exists, is refused where the key stands.
TEST(EquationCase, PluginInsteadOfEquations) {
  const auto c = EquationCase::load(example_path("vdp_plugin"));
  EXPECT_EQ(c.plugin(), std::string(SYMPATHY_SOURCE_DIR) + "/cases/examples/vdp_plugin.cpp");
  EXPECT_TRUE(c.system().derivatives.empty());
  const std::string states = "kind = \"equations\"\nplugin = \"PLUGIN\"\n[states]\nx = 1.0\n";
  expect_contains(error_of_file(replaced(states, "PLUGIN", "missing.cpp")),
                  ":2: key 'plugin': expected the name of a C++ source file (.cpp) beside the "
                  "case file or relative to it, got 'missing.cpp' (no such file)");
  expect_contains(error_of_file(replaced(states, "PLUGIN", "/etc/passwd")),
                  "key 'plugin': expected the name of a C++ source file (.cpp)");
  // A name that would be source lines if it reached the compiler (the attack of issue 32: a
  // newline, a statement, a #define) is refused where the key stands, before any file is read.
  expect_contains(
      error_of_file(replaced(
          states, "PLUGIN", R"(x\nstatic int s = __builtin_puts(\"SMUGGLED\");\n#define U a.cpp)")),
      ":2: key 'plugin': expected a file name of letters, digits and _ . / - only");
  const std::string source = write_test_file("sympathy_equation_case_test", ".cpp", "// empty\n");
  expect_contains(error_of_file(replaced(states, "PLUGIN", source) + "[equations]\nx = \"-x\"\n"),
                  "key 'equations': expected no [equations] in a case file with a plug-in");
}

TEST(EquationCase, ExamplesLoad) {
  for (const char* name : {"hopf", "lrz", "abc", "lcbp", "ffn", "row2_equations"}) {
    const auto c = EquationCase::load(example_path(name));
    EXPECT_EQ(c.name(), name);
    EXPECT_EQ(c.system().derivatives.size(), c.system().states.size());
    EXPECT_EQ(case_file_kind(example_path(name)), "equations");
  }
  const auto hopf = EquationCase::load(example_path("hopf"));
  EXPECT_EQ(hopf.state_names(), (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(hopf.parameter_names(), (std::vector<std::string>{"mu", "w"}));
  EXPECT_EQ(hopf.system().parameters[1].unit, "rad/s");
  EXPECT_EQ(hopf.parameter_values("fast")[1], 2.0);
  EXPECT_EQ(hopf.initial_state(&hopf.start("outside"))[0], 1.0);
  EXPECT_FALSE(hopf.system().uses_time);
  EXPECT_EQ(case_file_kind(std::string(SYMPATHY_SOURCE_DIR) + "/cases/row2.toml"), "metronomes");
}

TEST(EquationCase, OrderOfTheFileNotOfTheKeys) {
  const auto c =
      EquationCase::load(write_test_file("sympathy_equation_case_test", ".toml",
                                         replaced(kValid, "x = 1.0\ny = 0.0", "y = 0.0\nx = 1.0")));
  EXPECT_EQ(c.state_names(), (std::vector<std::string>{"y", "x"}));
  EXPECT_EQ(c.system().derivatives[0].name, "y");
}

TEST(EquationCase, UnknownNameIsLocatedToItsColumn) {
  const auto m = error_of_file(replaced(kValid, "\"a*x - b*y", "\"a*x - c*y"));
  // Line 11: x = "a*x - c*y ...": the 'c' stands in column 12.
  expect_contains(m,
                  ".toml:11:12: key 'equations.x': expected a state, a parameter, an "
                  "intermediate, t or pi (a, b, pi, r2, t, x, y), got the unknown name 'c'");
}

TEST(EquationCase, SyntaxErrorIsLocated) {
  const auto m = error_of_file(replaced(kValid, "\"b*x + a*y", "\"b*x + * y"));
  expect_contains(m,
                  ".toml:12:12: key 'equations.y': expected a number, a name, a function call "
                  "or '(', got '*'");
}

TEST(EquationCase, StateWithoutEquation) {
  const auto m = error_of_file(replaced(kValid, "y = \"b*x + a*y - y*r2\"\n", ""));
  expect_contains(m, ": table [equations]: expected an equation for every state, got none for 'y'");
}

TEST(EquationCase, EquationForUnknownState) {
  const auto m = error_of_file(kValid + "z = \"x\"\n");
  expect_contains(m,
                  ".toml:13:1: key 'equations.z': expected an equation for a state of [states] "
                  "(x, y), got 'z', not a state");
}

TEST(EquationCase, ParameterUsedButNotDefined) {
  const auto m = error_of_file(replaced(kValid, "a = 0.5\n", ""));
  expect_contains(m, "got the unknown name 'a'");
}

TEST(EquationCase, DuplicateNames) {
  auto m = error_of_file(replaced(kValid, "a = 0.5", "x = 0.5"));
  expect_contains(m,
                  ".toml:6:1: key 'parameters.x': expected a name that is not defined twice "
                  "(first at ");
  m = error_of_file(replaced(kValid, "r2 = ", "a = "));
  expect_contains(m, "key 'intermediates.a': expected a name that is not defined twice");
}

TEST(EquationCase, IntermediatesInOrder) {
  auto m = error_of_file(replaced(kValid, "r2 = \"x^2 + y^2\"", "r2 = \"q\"\nq = \"x\""));
  expect_contains(m,
                  ".toml:9:7: key 'intermediates.r2': expected names defined above this "
                  "intermediate, got 'q'");
  m = error_of_file(replaced(kValid, "r2 = \"x^2 + y^2\"", "r2 = \"r2 + 1\""));
  expect_contains(m, "expected names defined above this intermediate, got 'r2' itself");
}

TEST(EquationCase, ReservedNames) {
  const std::vector<std::pair<std::string, std::string>> bad{
      {"int", "is not a C++ keyword"},
      {"class", "is not a C++ keyword"},
      {"main", "is not a C++ keyword"},
      {"x__y", "has no \"__\""},
      {"_x", "starts with an ASCII letter"},
      {"sin", "is not a function of the grammar"},
      {"t", "is not built in"},
      {"pi", "is not built in"},
      {"\"a;b\"", "has only ASCII letters, digits and '_'"},
      {"\"a b\"", "has only ASCII letters, digits and '_'"},
      {"\"a}\"", "has only ASCII letters, digits and '_'"},
      {"\"#include\"", "starts with an ASCII letter"},
      {"1x", "starts with an ASCII letter"},
      {std::string(65, 'a'), "a name of at most 64 characters, got 65 characters"},
  };
  for (const auto& [name, expected] : bad) {
    const auto m = error_of_file(replaced(kValid, "a = 0.5", name + " = 0.5"));
    expect_contains(m, ".toml:6:1: key 'parameters.");
    expect_contains(m, expected);
  }
}

TEST(EquationCase, SmuggledCodeInExpressionsIsRefused) {
  const std::vector<std::pair<std::string, std::string>> bad{
      {"\"x; system(0)\"", "got ';'"},
      {"\"x } void f() {\"", "got '}'"},
      {"'x\" + \"y'", "got '\"'"},
      {"\"\"\"\n#include <cstdlib>\n\"\"\"", "got '#'"},
      {"\"x // y\"", "got '/'"},
      {"\"x \\u003b y\"", "expected an expression without escapes"},
      {"\"x \\\\ y\"", "expected an expression without escapes"},
      {"\"std::abs(x)\"", "got ':'"},
      {"1.5", "expected an expression in quotes"},
      // (Built by append: GCC 12 warns falsely, -Wrestrict, of "\"" + std::string(...).)
      {std::string("\"").append(5000, '1').append("\""), "expected at most 4000 characters"},
  };
  for (const auto& [expr, expected] : bad) {
    const auto m = error_of_file(replaced(kValid, "\"a*x - b*y - x*r2\"", expr));
    expect_contains(m, "key 'equations.x'");
    expect_contains(m, expected);
  }
  // A multi-line expression: its error is located on its own line.
  const auto m =
      error_of_file(replaced(kValid, "\"a*x - b*y - x*r2\"", "\"\"\"\na*x\n  ; y\"\"\""));
  expect_contains(m, ".toml:13:3: key 'equations.x': expected an operator");
}

TEST(EquationCase, NonAsciiAnywhereIsRefused) {
  auto m = error_of_file(replaced(kValid, "[states]", "[states] # \xce\xb1 the states"));
  expect_contains(m,
                  ".toml:2:12: expected ASCII text (an equation case file is ASCII throughout, "
                  "comments included), got byte 0xce");
  m = error_of_file(replaced(kValid, "x = 1.0", "\"x\xce\xb1\" = 1.0"));
  expect_contains(m, ".toml:3:3: expected ASCII text");
  m = error_of_file(replaced(kValid, "x = 1.0", "x = 1.0 # \x1b[2J"));
  expect_contains(m, "got byte 0x1b");
}

TEST(EquationCase, OverlongFileIsRefused) {
  const auto m = error_of_file(kValid + "# " + std::string(kMaxEquationFileBytes, 'x') + "\n");
  expect_contains(m, "expected an equation case file of at most 1048576 bytes");
}

TEST(EquationCase, MissingTablesAndKeys) {
  expect_contains(error_of_file(replaced(kValid, "kind = \"equations\"\n", "")),
                  "key 'kind' is missing: expected kind = \"equations\"");
  expect_contains(error_of_file(replaced(kValid, "[states]\nx = 1.0\ny = 0.0\n", "")),
                  "table [states] is missing");
  expect_contains(error_of_file(kValid + "[extra]\n"),
                  ":13: key 'extra': expected one of the keys kind, name,");
  expect_contains(error_of_file(replaced(kValid, "unit = \"1/s\"", "units = \"1/s\"")),
                  "key 'parameters.b.units': expected one of the keys value, unit, min, max");
  expect_contains(error_of_file(replaced(kValid, "x = 1.0", "x = \"1.0\"")),
                  "key 'states.x': expected a number, got \"1.0\"");
  expect_contains(error_of_file(replaced(kValid, "[states]", "[states\n")), "not valid TOML");
}

TEST(EquationCase, BoundsAreChecked) {
  expect_contains(error_of_file(replaced(kValid, "value = 2.0", "value = 20.0")),
                  "key 'parameters.b.value': expected a value within [0, 10], got 20");
  const auto c =
      EquationCase::load(write_test_file("sympathy_equation_case_test", ".toml", kValid));
  const auto m =
      input_error_of([&] { c.parameter_values("", {parse_assignment("b=-1", "--set")}); });
  expect_contains(m, "--set b=-1: expected a value of b within [0, 10]");
  expect_contains(
      input_error_of([&] { c.parameter_values("", {parse_assignment("q=1", "--set")}); }),
      "--set q=1: unknown parameter 'q'; expected one of: a, b");
  EXPECT_EQ(c.parameter_values("", {parse_assignment("b=3", "--set")})[1], 3.0);
  // A parameter set out of bounds is refused on load, whether it is used or not.
  expect_contains(error_of_file(kValid + "[params.wide]\nb = 11.0\n"),
                  ".toml:14: key 'params.wide.b': expected a value of b within [0, 10]");
}

TEST(EquationCase, TimeMakesTheSystemNonautonomous) {
  const auto c =
      EquationCase::load(write_test_file("sympathy_equation_case_test", ".toml",
                                         replaced(kValid, "\"b*x + a*y", "\"cos(t) + b*x + a*y")));
  EXPECT_TRUE(c.system().uses_time);
}

// forcing_period: an expression of the parameters, positive at the file's values, for equations
// that use t; anything else refused where it stands.
TEST(EquationCase, ForcingPeriod) {
  const std::string forced = replaced(kValid, "\"b*x + a*y", "\"cos(b*t) + b*x + a*y");
  const auto c = EquationCase::load(
      write_test_file("sympathy_equation_case_test", ".toml",
                      replaced(forced, "[states]", "forcing_period = \"2*pi/b\"\n[states]")));
  ASSERT_TRUE(c.system().forcing_period.has_value());
  expect_contains(error_of_file(replaced(kValid, "[states]", "forcing_period = \"1\"\n[states]")),
                  ".toml:2: key 'forcing_period': expected no forcing_period for equations "
                  "that do not use t");
  expect_contains(
      error_of_file(replaced(forced, "[states]", "forcing_period = \"2*pi/x\"\n[states]")),
      ".toml:2:24: key 'forcing_period': expected parameters, numbers and pi only (the forcing's "
      "period does not change along the motion), got 'x'");
  expect_contains(
      error_of_file(replaced(forced, "[states]", "forcing_period = \"a - 1\"\n[states]")),
      ".toml:2: key 'forcing_period': expected a positive value at the file's parameter values, "
      "got -0.5");
  expect_contains(error_of_file(replaced(forced, "[states]", "forcing_period = 2\n[states]")),
                  "key 'forcing_period'");
}

TEST(EquationCase, MetronomeCaseFileRefusesEquations) {
  const std::string path = write_test_file("sympathy_equation_case_test", ".toml", kValid);
  expect_contains(input_error_of([&] { CaseFile::load(path); }),
                  ":1: key 'kind': expected a metronome case file here");
}

}  // namespace
}  // namespace sympathy
