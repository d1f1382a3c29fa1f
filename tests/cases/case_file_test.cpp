#include "sympathy/cases/case_file.hpp"
#include "tests/support/cases.hpp"
#include "tests/support/errors.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace sympathy {
namespace {

using testing::case_path;
using testing::expect_mentions;
using testing::load_spec;
using testing::random_state;

// A small valid row case; tests replace one line to make one mistake.
const std::string kValid = R"(name = "tiny"
escapement = "half"
default_params = "base"

[platform]
directions = 1

[metronome]
mp = 0.0185
mb = 0.0086
lp = 0.0245
lb = 0.027
d = 2.4e-6
s = 4.51e-5
ths = 0.1920
the = 0.2793
eps = 0.05

[[metronomes]]
angle = 0
[[metronomes]]
angle = 0

[params.base]
M = 0.3778
c = 0.0185
k = 14.7467

[starts.in-phase]
th1 = 0.3
th2 = 0.3
invariant = ["th2 = th1"]
)";

class CaseFileErrors : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    return path_ = testing::write_test_file("sympathy_case_tests", ".toml", text);
  }
  // kValid with `from` replaced by `to` (which must occur).
  std::string write_changed(const std::string& from, const std::string& to) {
    std::string text = kValid;
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    return write(text);
  }
  template <class F>
  std::string error_of(F&& f) {
    return testing::input_error_of(f);
  }
  std::string path_;
};

TEST_F(CaseFileErrors, ValidFileLoads) {
  const auto c = CaseFile::load(write(kValid));
  EXPECT_EQ(c.name(), "tiny");
  EXPECT_EQ(c.parameter_set_names(), std::vector<std::string>{"base"});
  const auto spec = c.spec();
  EXPECT_EQ(spec.M, 0.3778);
  EXPECT_EQ(spec.metronomes.size(), 2u);
  const auto z = c.initial_state(&c.start("in-phase"));
  EXPECT_EQ(z[1], 0.3);
  EXPECT_EQ(z[2], 0.3);
}

TEST_F(CaseFileErrors, UnknownTopLevelKey) {
  const auto path = write_changed("name = \"tiny\"", "name = \"tiny\"\ncolour = \"red\"");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":2", "'colour'", "unknown key"});
}

TEST_F(CaseFileErrors, UnknownNestedKey) {
  const auto path = write_changed("mp = 0.0185", "mpp = 0.0185");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":9", "'metronome.mpp'", "unknown key"});
}

TEST_F(CaseFileErrors, MissingKey) {
  const auto path = write_changed("d = 2.4e-6\n", "");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path, "'metronomes[1].d'", "missing", "[metronome]"});
}

TEST_F(CaseFileErrors, MissingMetronomes) {
  const auto path = write_changed("[[metronomes]]\nangle = 0\n[[metronomes]]\nangle = 0\n", "");
  expect_mentions(error_of([&] { CaseFile::load(path); }), {path, "'metronomes'", "missing"});
}

TEST_F(CaseFileErrors, WrongType) {
  const auto path = write_changed("mp = 0.0185", "mp = \"heavy\"");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":9", "'metronome.mp'", "expected a number", "\"heavy\""});
}

TEST_F(CaseFileErrors, NonPositiveMass) {
  const auto path = write_changed("mp = 0.0185", "mp = -0.0185");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":9", "metronome.mp", "positive"});
}

TEST_F(CaseFileErrors, NonPositiveLength) {
  const auto path = write_changed("[[metronomes]]\nangle = 0\n[[metronomes]]",
                                  "[[metronomes]]\nangle = 0\n[[metronomes]]\nlp = 0.0");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":22", "metronomes[2].lp", "positive"});
}

TEST_F(CaseFileErrors, NotANumber) {
  const auto path = write_changed("d = 2.4e-6", "d = nan");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":13", "'metronome.d'", "finite"});
}

TEST_F(CaseFileErrors, SpringToMissingMetronome) {
  const auto path = write_changed("[params.base]",
                                  "[[springs]]\nbetween = [1, 5]\nkappa = 0.01\n\n[params.base]");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":25", "springs[1].between", "two different metronomes among 1..2"});
}

// Metronome numbers beyond int's range were cast to int before the range check: -2147483648
// became INT_MIN and "- 1" overflowed (undefined behaviour, a UBSan report through the case-file
// fuzz target), and 4294967297 became 1, so the spring was silently put on metronome 1.
TEST_F(CaseFileErrors, SpringNumbersBeyondIntRange) {
  for (const std::string between :
       {"[-2147483648, 1]", "[4294967297, 2]", "[1, 9223372036854775807]"}) {
    const auto path = write_changed(
        "[params.base]", "[[springs]]\nbetween = " + between + "\nkappa = 0.01\n\n[params.base]");
    expect_mentions(error_of([&] { CaseFile::load(path); }),
                    {path + ":25", "springs[1].between", "two different metronomes among 1..2"});
  }
}

TEST_F(CaseFileErrors, UnknownParameterSet) {
  const auto c = CaseFile::load(write(kValid));
  expect_mentions(error_of([&] { c.spec("table9"); }),
                  {"--params table9", path_, "expected one of: base"});
}

TEST_F(CaseFileErrors, UnknownStart) {
  const auto c = CaseFile::load(write(kValid));
  expect_mentions(error_of([&] { c.start("sideways"); }),
                  {"--start sideways", path_, "expected one of: in-phase"});
}

TEST_F(CaseFileErrors, UnknownParameterInSet) {
  const auto path = write_changed("k = 14.7467", "k = 14.7467\nQ = 3");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":28", "'params.base.Q'", "a parameter of the model"});
}

TEST_F(CaseFileErrors, BadAssignments) {
  const auto c = CaseFile::load(write(kValid));
  expect_mentions(error_of([&] { c.spec("", {parse_assignment("Mass=1", "--set")}); }),
                  {"--set Mass=1", "unknown parameter 'Mass'"});
  expect_mentions(error_of([&] { parse_assignment("M=heavy", "--set"); }),
                  {"--set M=heavy", "expected a finite number"});
  expect_mentions(error_of([&] { parse_assignment("M", "--set"); }), {"--set M", "KEY=VALUE"});
  expect_mentions(error_of([&] { c.spec("", {parse_assignment("M=-1", "--set")}); }),
                  {"--set M=-1", "positive", "-1"});
  expect_mentions(
      error_of([&] { c.initial_state(nullptr, {parse_assignment("phi=1", "--initial")}); }),
      {"--initial phi=1", "unknown state 'phi'", "th1"});
}

TEST_F(CaseFileErrors, BadEscapement) {
  const auto path = write_changed("escapement = \"half\"", "escapement = \"smooth\"");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":2", "'escapement'", "\"half\", \"double\" or \"impulsive\""});
}

TEST_F(CaseFileErrors, UnknownDefaultParams) {
  const auto path = write_changed("default_params = \"base\"", "default_params = \"table2\"");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":3", "'default_params'", "[params.NAME]"});
}

TEST_F(CaseFileErrors, SyntaxError) {
  const auto path = write_changed("[platform]", "[platform");
  expect_mentions(error_of([&] { CaseFile::load(path); }), {path + ":5", "not valid TOML"});
}

TEST_F(CaseFileErrors, BadInvariantRelation) {
  const auto path = write_changed("invariant = [\"th2 = th1\"]", "invariant = [\"th2 = th7\"]");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":32", "starts.in-phase.invariant", "positions", "th2 = th7"});
}

TEST_F(CaseFileErrors, NoPlatformMass) {
  const auto path = write_changed("M = 0.3778\n", "");
  const auto c = CaseFile::load(path);
  expect_mentions(error_of([&] { c.spec(); }), {path, "no value for parameter 'M'", "--set M="});
}

TEST_F(CaseFileErrors, BadDirections) {
  const auto path = write_changed("directions = 1", "directions = 3");
  expect_mentions(error_of([&] { CaseFile::load(path); }),
                  {path + ":6", "platform.directions", "1 (x) or 2"});
}

TEST_F(CaseFileErrors, TopHeavyPendulum) {
  const auto path = write_changed("mb = 0.0086", "mb = 0.086");
  expect_mentions(error_of([&] { CaseFile::load(path); }), {path, "mp*lp > mb*lb"});
}

TEST_F(CaseFileErrors, MissingFile) {
  expect_mentions(error_of([] { CaseFile::load("/nonexistent/case.toml"); }),
                  {"/nonexistent/case.toml", "cannot read"});
}

// The shipped case files load, with the paper's tables under their names (MODEL.md).
TEST(CaseFiles, PaperTablesByName) {
  const auto row = CaseFile::load(case_path("row2"));
  EXPECT_EQ(row.spec("table2").kx, 14.7467);
  EXPECT_EQ(row.spec("table3").cx, 0.3868);
  EXPECT_EQ(row.start_names(),
            (std::vector<std::string>{"in-phase", "anti-phase", "in-phase-low"}));
  const auto cross = CaseFile::load(case_path("cross4"));
  EXPECT_EQ(cross.spec("table4").M, 0.6366);
  EXPECT_EQ(cross.spec("table5").ky, 62.8719);
  EXPECT_EQ(cross.start_names(), (std::vector<std::string>{"in-in", "anti-anti", "in-anti"}));
  const auto spring = CaseFile::load(case_path("cross4_spring"));
  EXPECT_EQ(spring.spec("table5").cx, 0.2673);
  ASSERT_EQ(spring.spec().springs.size(), 1u);
  EXPECT_EQ(spring.spec().springs[0].kappa, 0.01);
  EXPECT_EQ(spring.spec().springs[0].first, 0);
  EXPECT_EQ(spring.spec().springs[0].second, 2);
  // Table I in SI units (spec() returns a ModelSpec by value: keep it, not a reference into it).
  const ModelSpec spec = row.spec();
  const auto& m = spec.metronomes[0].values;
  EXPECT_EQ(m.at("d"), 2.4e-6);
  EXPECT_EQ(m.at("s"), 4.51e-5);
}

}  // namespace
}  // namespace sympathy
