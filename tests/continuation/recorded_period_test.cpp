// An orbit started from one recorded period (continuation/recorded_period.hpp): a period written
// from an orbit and read back gives the same orbit, a longer recording its first return, and bad
// files located errors before any work.
#include "sympathy/continuation/recorded_period.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "sympathy/core/csv.hpp"
#include "tests/support/errors.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::expect_mentions;

using testing::kTwoPi;

// `periods` periods of the orbit through z0, `per_period` rows each (plus the last), written as
// `sympathy simulate --out` writes them: t, then the states by name, shortest round-trip numbers.
std::string write_periods(const OdeSystem& system, const Eigen::VectorXd& z0, double period,
                          int per_period, int periods, const std::string& name) {
  const std::string path = testing::write_test_file("sympathy_recorded_period", name + ".csv", "");
  std::vector<std::string> header{"t"};
  for (const auto& s : system.state_names()) header.push_back(s);
  CsvWriter csv(path, header);
  FlowOptions accurate;
  accurate.rtol = 1e-12;
  accurate.atol = 1e-14;
  Flow flow(system, accurate);
  std::vector<double> times;
  for (int k = 0; k <= per_period * periods; ++k) times.push_back(k * period / per_period);
  flow.sample(z0, system.default_parameters(), 0.0, times, [&](double t, const Eigen::VectorXd& z) {
    std::vector<double> row{t};
    for (int i = 0; i < z.size(); ++i) row.push_back(z[i]);
    csv.row(row);
  });
  csv.close();
  return path;
}

// The Hopf cycle with a transverse state (tests/support/test_systems.hpp): the unit circle,
// w = 0, period 2 pi exactly.
class RecordedPeriodTest : public ::testing::Test {
 protected:
  testing::HopfCycle system{true};
  PeriodicOrbit reference() {
    const PeriodicOrbit o =
        find_periodic_orbit(system, system.default_parameters(), Eigen::Vector3d(1.2, 0.0, 0.1),
                            InvariantSubspace(), OrbitOptions());
    EXPECT_TRUE(o.converged());
    return o;
  }
};

// A period written from a converged orbit and read back: its first row is the orbit's state to
// the last bit (shortest round-trip numbers), its span the period; Newton from it lands on the
// same orbit. Both orbits converge to Newton's tolerance (20 rtol = 2e-10 at rtol 1e-11) from
// the same section, so they agree to 1e-9; against the exact circle (radius 1, period 2 pi) to
// the integration's accuracy, 1e-8 relative as in periodic_orbit_test.
TEST_F(RecordedPeriodTest, SimulatedPeriodReadsBackTheSameOrbit) {
  const PeriodicOrbit original = reference();
  const std::string path = write_periods(system, original.state0, original.period, 200, 1, "one");
  const RecordedPeriod r = read_recorded_period(path, system.state_names());
  EXPECT_EQ(r.rows, 201);
  EXPECT_EQ(r.state0, original.state0);
  EXPECT_NEAR(r.span, original.period, 1e-12);
  EXPECT_NEAR(r.period, original.period, 1e-6);  // the span, or a return in the last interval
  const PeriodicOrbit orbit = orbit_from_recorded_period(system, system.default_parameters(), r,
                                                         InvariantSubspace(), OrbitOptions());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_LT((orbit.state0 - original.state0).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(orbit.period, original.period, 1e-9);
  EXPECT_NEAR(orbit.period, kTwoPi, kTwoPi * 1e-8);
  EXPECT_NEAR(orbit.state0.head(2).norm(), 1.0, 1e-8);
  EXPECT_NEAR(orbit.state0[2], 0.0, 1e-8);
}

// Three periods at 50 rows each: the guess is the first return (between rows 50 and 51, line 52
// past it), the chord's crossing of the section 2 pi within the interpolation's error (the
// sampling step 0.126 squared, about 1e-2, as a bound), and Newton gives the same orbit.
TEST_F(RecordedPeriodTest, LongerRecordingGivesItsFirstReturn) {
  const PeriodicOrbit original = reference();
  const std::string path = write_periods(system, original.state0, original.period, 50, 3, "three");
  const RecordedPeriod r = read_recorded_period(path, system.state_names());
  EXPECT_TRUE(r.returned);
  EXPECT_EQ(r.rows, 151);
  EXPECT_NEAR(r.span, 3 * original.period, 1e-12);
  EXPECT_NEAR(r.period, original.period, 1e-2);
  EXPECT_GE(r.return_line, 51);
  EXPECT_LE(r.return_line, 53);
  const PeriodicOrbit orbit = orbit_from_recorded_period(system, system.default_parameters(), r,
                                                         InvariantSubspace(), OrbitOptions());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_LT((orbit.state0 - original.state0).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(orbit.period, original.period, 1e-9);
}

// Columns in any order, and a recording that does not start at t = 0.
TEST_F(RecordedPeriodTest, ColumnsInAnyOrderAndAnyStartTime) {
  std::string text = "t,w,y,x\n";
  for (int k = 0; k <= 40; ++k) {
    const double t = k * kTwoPi / 40;
    text += format_double(10.0 + t) + ",0," + format_double(std::sin(t)) + "," +
            format_double(std::cos(t)) + "\n";
  }
  const std::string path = testing::write_test_file("sympathy_recorded_period", ".csv", text);
  const RecordedPeriod r = read_recorded_period(path, system.state_names());
  EXPECT_EQ(r.state0, Eigen::Vector3d(1.0, 0.0, 0.0));
  EXPECT_EQ(r.start_time, 10.0);
  EXPECT_NEAR(r.span, kTwoPi, 1e-12);
  const PeriodicOrbit orbit = orbit_from_recorded_period(system, system.default_parameters(), r,
                                                         InvariantSubspace(), OrbitOptions());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_NEAR(orbit.period, kTwoPi, kTwoPi * 1e-8);
}

class RecordedPeriodErrors : public ::testing::Test {
 protected:
  std::string error_of(const std::string& text) {
    path_ = testing::write_test_file("sympathy_recorded_period", ".csv", text);
    return testing::input_error_of([&] {
      read_recorded_period(path_, {"x", "y"}, "cases/examples/lcbp.toml");
    });
  }
  std::string path_;
};

// A circle of `rows` rows over `fraction` of a period.
std::string circle(int rows, double fraction, const std::string& header = "t,x,y") {
  std::string text = header + "\n";
  for (int k = 0; k < rows; ++k) {
    const double t = fraction * k / (rows - 1);
    text += format_double(t) + "," + format_double(std::cos(kTwoPi * t)) + "," +
            format_double(std::sin(kTwoPi * t)) + "\n";
  }
  return text;
}

TEST_F(RecordedPeriodErrors, MissingStateColumn) {
  expect_mentions(error_of("t,x\n0,1\n0.1,0.8\n0.2,0.3\n0.3,-0.3\n"),
                  {path_ + ":1:", "no column 'y'", "cases/examples/lcbp.toml", "x, y"});
}

TEST_F(RecordedPeriodErrors, ColumnNotAState) {
  expect_mentions(error_of("t,x,y,z\n0,1,0,0\n"),
                  {path_ + ":1:", "column 4 'z'", "not a state of cases/examples/lcbp.toml"});
}

TEST_F(RecordedPeriodErrors, TimeNotIncreasing) {
  expect_mentions(error_of("t,x,y\n0,1,0\n0.25,0,1\n0.25,-1,0\n0.75,0,-1\n1,1,0\n"),
                  {path_ + ":4:", "column 't'", "strictly increasing"});
}

TEST_F(RecordedPeriodErrors, TooFewRows) {
  expect_mentions(error_of("t,x,y\n0,1,0\n0.5,-1,0\n1,1,0\n"),
                  {path_, "3 rows", "at least 4", "too short"});
}

// Half a period: the last row is the diametrically opposite point, and no return.
TEST_F(RecordedPeriodErrors, LessThanOnePeriod) {
  expect_mentions(error_of(circle(21, 0.5)),
                  {path_ + ":22:", "from the first (line 2", "never comes back", "too short"});
}

TEST_F(RecordedPeriodErrors, StateDoesNotMove) {
  expect_mentions(error_of("t,x,y\n0,1,0\n0.1,1,0\n0.2,0,1\n0.3,-1,0\n"),
                  {path_ + ":3:", "the same state as line 2"});
}

TEST_F(RecordedPeriodErrors, NotANumber) {
  expect_mentions(error_of("t,x,y\n0,1,0\n0.1,abc,0\n"),
                  {path_ + ":3:", "column 'x'", "expected a number"});
}

// A whole period and a bit more reads: the return is found near the end.
TEST_F(RecordedPeriodErrors, OnePeriodAndABitReads) {
  path_ = testing::write_test_file("sympathy_recorded_period", ".csv", circle(45, 1.1));
  const RecordedPeriod r = read_recorded_period(path_, {"x", "y"});
  EXPECT_TRUE(r.returned);
  EXPECT_NEAR(r.period, 1.0, 1e-2);
}

}  // namespace
}  // namespace sympathy
