#include "sympathy/continuation/branch_point.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/continuation/continuation.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::CrossingCircles;

// BDF at rtol 1e-11 (the library's default integrator), or the CLI's default preset: Adams with
// the variational equations appended, rtol 5e-12 (cases/cli/common.cpp, apply_accuracy).
FlowOptions flow(bool preset) {
  FlowOptions f;
  f.rtol = preset ? 5e-12 : 1e-11;
  f.atol = 1e-2 * f.rtol;
  if (preset) {
    f.method = Method::Adams;
    f.nonlinear_solver = NonlinearSolver::FixedPoint;
    f.sensitivities = Sensitivities::Augmented;
  }
  return f;
}

ContinuationOptions options(double lower, double upper, bool preset) {
  ContinuationOptions o;
  o.lower = lower;
  o.upper = upper;
  o.orbit.shooting.flow = flow(preset);
  return o;
}

// The circle r = radius of CrossingCircles, corrected: period 1.
PeriodicOrbit circle(const OdeSystem& system, const ParameterValues& p, double radius) {
  Eigen::VectorXd z(2);
  z << radius, 0.0;
  const auto orbit = solve_periodic_orbit(system, p, z, 1.0, {}, OrbitOptions{});
  EXPECT_TRUE(orbit.converged()) << orbit.newton.reason;
  return orbit;
}

// AUTO's lcbp: along the circle r = p2 the radial multiplier exp(-p2 (p2 - p1)) crosses +1 at
// p1 = p2 exactly, where the family r = p1 crosses it. The crossing alone put it 4.4e-5 off with
// BDF (1.8e-8 with the CLI's preset: its corrected orbit 8.7e-9 inside the circle, its bracket
// claiming 1e-8). On the regular system: within the reported uncertainty, itself below 1e-8 (BDF:
// error 8.5e-10, uncertainty 1.8e-9, the shooting residual's own error 3.4e-9), and with the
// preset within 1e-10 (measured 1.4e-11, uncertainty 4e-11); its orbit on the circle.
TEST(BranchPoint, TranscriticalCrossingOfCirclesLocatedOnTheRegularSystem) {
  for (const bool preset : {false, true})
    for (const double p2 : {2.0, 1.5}) {
      SCOPED_TRACE(std::string(preset ? "preset" : "BDF") + ", p2 = " + std::to_string(p2));
      const CrossingCircles system(p2 - 1.0, p2);
      const auto start = circle(system, system.default_parameters(), p2);
      Continuation c(system, 0, options(p2 - 1.0, p2 + 1.0, preset));
      const Branch branch = c.run(start, +1);
      ASSERT_EQ(branch.events.size(), 1u) << branch.stop_reason;
      const Bifurcation& bp = branch.events[0];
      EXPECT_EQ(bp.type, BifurcationType::BranchPoint);
      EXPECT_TRUE(bp.trusted()) << bp.note;
      EXPECT_NE(bp.note.find("regular BP system"), std::string::npos) << bp.note;
      EXPECT_LE(std::abs(bp.parameter - p2), bp.uncertainty);
      EXPECT_LE(bp.uncertainty, 1e-8);
      if (preset) {
        EXPECT_NEAR(bp.parameter, p2, 1e-10);
      }
      EXPECT_NEAR(bp.state0.norm(), p2, preset ? 1e-10 : 1e-8);
      EXPECT_NEAR(bp.period, 1.0, 1e-9);
      EXPECT_NEAR(bp.crossing.real(), 1.0, 1e-8);
    }
}

// The system is regular, not a polish of an already good point: from a guess 1e-3 off in the
// parameter and 1e-3 off the circle (in the section, the x axis), Newton lands on
// (p1, r) = (2, 2) to 1e-10 with the CLI's preset, with beta (how far F is from having a branch
// point) zero to 1e-10 and the parameter within the uncertainty reported.
TEST(BranchPoint, NewtonConvergesFromAFarGuess) {
  const CrossingCircles system(2.0, 2.0);
  ShootingOptions shooting;
  shooting.flow = flow(true);
  ShootingProblem problem(system, shooting);
  Eigen::VectorXd z(2);
  z << 2.0, 0.0;
  const PhaseSection section{z, Eigen::Vector2d(0.0, 1.0)};  // the x axis: y = 0
  BranchSpace space(system, problem, 0, system.default_parameters(), 2.0, 1e-10);
  space.reset_scales(z, 1.0, shooting.flow);
  Eigen::VectorXd guess(4);
  guess << 2.001, 0.0, 1.0, 2.001;
  const auto s = solve_branch_point(problem, section, space, 0, guess, 1e-10, 1e-10);
  ASSERT_TRUE(s.converged) << s.reason;
  EXPECT_NEAR(s.y[3], 2.0, 1e-10);
  EXPECT_NEAR(s.y[0], 2.0, 1e-10);
  EXPECT_NEAR(s.y[1], 0.0, 1e-10);
  EXPECT_NEAR(s.y[2], 1.0, 1e-10);
  EXPECT_NEAR(s.beta, 0.0, 1e-10);
  EXPECT_LE(std::abs(s.y[3] - 2.0), s.uncertainty);
  EXPECT_LE(s.residual, 1e-10);
  EXPECT_GE(s.iterations, 2);  // it had to move
}

// Where the regular system is not solved (here: 21 segments, 44 unknowns with the parameter,
// above the 41 its differences are affordable for), the crossing's point stays, and its
// uncertainty covers its error at a transcritical crossing (about the square root of the
// residual's error) instead of claiming the bracket's 1e-8: measured error 3.3e-7, uncertainty
// 6.3e-5.
TEST(BranchPoint, CrossingAloneReportsAnHonestUncertainty) {
  const CrossingCircles system(1.0, 2.0);
  const auto start = circle(system, system.default_parameters(), 2.0);
  ContinuationOptions o = options(1.0, 3.0, false);
  o.orbit.shooting.segments = 21;
  Continuation c(system, 0, o);
  const Branch branch = c.run(start, +1);
  ASSERT_EQ(branch.events.size(), 1u) << branch.stop_reason;
  const Bifurcation& bp = branch.events[0];
  EXPECT_NE(bp.note.find("located by the crossing alone"), std::string::npos) << bp.note;
  EXPECT_NE(bp.note.find("44 unknowns"), std::string::npos) << bp.note;
  EXPECT_LE(std::abs(bp.parameter - 2.0), bp.uncertainty);
  EXPECT_LE(bp.uncertainty, 1e-3);
}

// A problem too large for the differences is refused with the reason, before any work.
TEST(BranchPoint, TooManyUnknownsRefused) {
  const CrossingCircles system(2.0, 2.0);
  ShootingOptions shooting;
  shooting.segments = 30;  // 61 unknowns and the parameter
  ShootingProblem problem(system, shooting);
  BranchSpace space(system, problem, 0, system.default_parameters(), 2.0, 1e-10);
  const auto s = solve_branch_point(problem, PhaseSection{}, space, 0, Eigen::VectorXd::Zero(62),
                                    1e-10, 1e-10);
  EXPECT_FALSE(s.converged);
  EXPECT_NE(s.reason.find("62 unknowns"), std::string::npos) << s.reason;
  EXPECT_EQ(s.evaluations, 0);
}

}  // namespace
}  // namespace sympathy
