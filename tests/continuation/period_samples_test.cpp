// The period sampled by the shooting run that confirms an orbit (PeriodSamples), which the
// branch's scales and the describers read instead of integrating the period once more: against
// the exact cycle, on every integrator and with several segments.
#include <gtest/gtest.h>

#include <cmath>

#include "sympathy/continuation/branch_space.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::HopfCycle;

struct Setting {
  const char* name;
  Method method;
  Sensitivities sensitivities;
  NonlinearSolver solver;
};

const Setting kSettings[] = {
    {"BDF, forward module", Method::BDF, Sensitivities::ForwardModule, NonlinearSolver::Newton},
    {"Adams, augmented", Method::Adams, Sensitivities::Augmented, NonlinearSolver::FixedPoint},
    {"ERK, augmented", Method::ERK, Sensitivities::Augmented, NonlinearSolver::FixedPoint},
};

OrbitOptions options(const Setting& s, int segments) {
  OrbitOptions o;
  o.shooting.segments = segments;
  o.shooting.flow.method = s.method;
  o.shooting.flow.sensitivities = s.sensitivities;
  o.shooting.flow.nonlinear_solver = s.solver;
  o.shooting.flow.rtol = 1e-10;
  o.shooting.flow.atol = 1e-12;
  o.newton.residual_tolerance = 1e-9;
  return o;
}

// Exact: the unit circle traversed at unit speed, z(t) = (cos(t + phi), sin(t + phi)), period
// 2 pi. Each sample within 2e-8 of it (the shooting flow at rtol 1e-10: measured 1e-9 or better;
// the cubic Hermite interpolant of the ERK steps, h^4/384 at steps of about 0.05, 2e-8 at worst),
// both ends on z0, with one segment and with three (the samples of each read off its own run).
TEST(PeriodSamples, TheExactCycleOnEveryIntegrator) {
  HopfCycle system;
  Eigen::VectorXd guess(2);
  guess << 1.1, 0.05;
  for (const auto& s : kSettings)
    for (int segments : {1, 3}) {
      SCOPED_TRACE(std::string(s.name) + ", segments " + std::to_string(segments));
      const PeriodicOrbit orbit = solve_periodic_orbit(system, system.default_parameters(), guess,
                                                       6.0, {}, options(s, segments));
      ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
      ASSERT_TRUE(orbit.samples.of(orbit.state0, orbit.period));
      const int intervals = PeriodSamples::intervals;
      const double phi = std::atan2(orbit.state0[1], orbit.state0[0]);
      double worst = 0.0;
      for (int k = 0; k <= intervals; ++k) {
        const double t = orbit.period * k / intervals;
        const Eigen::Vector2d exact(std::cos(t + phi), std::sin(t + phi));
        worst = std::max(worst, (orbit.samples.states.col(k) - exact).cwiseAbs().maxCoeff());
      }
      EXPECT_LT(worst, 2e-8);
      EXPECT_EQ(orbit.samples.states.col(0), orbit.state0);
      EXPECT_LT((orbit.samples.states.col(intervals) - orbit.state0).cwiseAbs().maxCoeff(), 1e-8);
    }
}

// sample_period reads the orbit's samples where they are its own, and integrates where they are
// not (an orbit whose state or period was moved afterwards); what it reads is closer to the
// exact cycle than what it integrates.
TEST(PeriodSamples, SamplePeriodReadsThemOnlyWhereTheyAreTheOrbits) {
  HopfCycle system;
  Eigen::VectorXd guess(2);
  guess << 1.1, 0.05;
  PeriodicOrbit orbit = solve_periodic_orbit(system, system.default_parameters(), guess, 6.0, {},
                                             options(kSettings[1], 1));
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  std::vector<Eigen::VectorXd> read, integrated;
  sample_period(system, orbit, [&](double, const Eigen::VectorXd& z) { read.push_back(z); });
  PeriodicOrbit moved = orbit;
  moved.state0[0] += 1e-12;  // no longer the samples' first state: integrated
  EXPECT_FALSE(moved.samples.of(moved.state0, moved.period));
  moved.state0 = orbit.state0;
  moved.period += 1e-12;
  EXPECT_FALSE(moved.samples.of(moved.state0, moved.period));
  PeriodicOrbit without = orbit;
  without.samples = PeriodSamples{};
  sample_period(system, without,
                [&](double, const Eigen::VectorXd& z) { integrated.push_back(z); });
  ASSERT_EQ(read.size(), static_cast<std::size_t>(PeriodSamples::intervals + 1));
  ASSERT_EQ(integrated.size(), read.size());
  const double phi = std::atan2(orbit.state0[1], orbit.state0[0]);
  double read_error = 0.0, integrated_error = 0.0;
  for (std::size_t k = 0; k < read.size(); ++k) {
    EXPECT_EQ(read[k], orbit.samples.states.col(static_cast<Eigen::Index>(k)));
    const double t = orbit.period * static_cast<double>(k) / PeriodSamples::intervals;
    const Eigen::Vector2d exact(std::cos(t + phi), std::sin(t + phi));
    read_error = std::max(read_error, (read[k] - exact).cwiseAbs().maxCoeff());
    integrated_error = std::max(integrated_error, (integrated[k] - exact).cwiseAbs().maxCoeff());
  }
  // The plain run at rtol 1e-9 is off by up to 1.5e-8 (measured); the shooting run's samples
  // (rtol 1e-10, sensitivities in the error test) are closer.
  EXPECT_LT(integrated_error, 1e-7);
  EXPECT_LT(read_error, integrated_error);
}

// A branch's scales from the samples equal those from a run of their own (the same times,
// T k / 100): within 1e-7 relative on the transverse Hopf cycle (x and y of size 1, w of 0; the
// run of their own, at the transient flow's rtol 1e-8, is off by 4e-8: measured), and the largest
// of 100 samples of a cosine is within (pi/100)^2/2 = 5e-4 of 1.
TEST(PeriodSamples, BranchScalesFromTheSamplesEqualSampledOnes) {
  HopfCycle system(true);
  Eigen::VectorXd guess(3);
  guess << 1.1, 0.05, 0.0;
  const ParameterValues p = system.default_parameters();
  const OrbitOptions o = options(kSettings[0], 1);
  const PeriodicOrbit orbit = solve_periodic_orbit(system, p, guess, 6.0, {}, o);
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  ShootingProblem problem(system, o.shooting);
  BranchSpace from_samples(system, problem, 0, p, 1.0, 1e-9);
  BranchSpace from_run(system, problem, 0, p, 1.0, 1e-9);
  from_samples.reset_scales(orbit.state0, orbit.period, o.transient_flow, &orbit.samples);
  from_run.reset_scales(orbit.state0, orbit.period, o.transient_flow);
  ASSERT_EQ(from_samples.sizes().size(), 3);
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(from_samples.sizes()[i], from_run.sizes()[i], 1e-7 * from_run.sizes().maxCoeff())
        << "component " << i;
  EXPECT_NEAR(from_samples.sizes()[0], 1.0, 5e-4);
}

}  // namespace
}  // namespace sympathy
