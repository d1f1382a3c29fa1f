#include "sympathy/continuation/corrector.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cases/bench/hand_written_systems.hpp"

namespace sympathy {
namespace {

using bench::HandHopf;

// Corrects the orbit guessed through (r, 0) with period 2 pi on the Hopf normal form
// r' = mu r - r^3, theta' = 1 (HandHopf, w = 1), with mu held at its value (the arclength
// condition along the parameter, step 0), as a continuation's corrector does.
Correction correct_at(double mu, double r) {
  const HandHopf system(Eigen::Vector2d(mu, 1.0));
  const ParameterValues p = system.default_parameters();
  ShootingProblem problem(system, ShootingOptions{});
  problem.record_samples(true);  // as a continuation's problem: each point's period sampled
  const Eigen::Vector2d z0(r, 0.0);
  const double period = 2 * std::numbers::pi;
  BranchSpace space(system, problem, 0, p, 1.0, 1e-10);
  space.reset_scales(z0, period, FlowOptions{});
  const int N = problem.unknowns();
  Eigen::VectorXd y(N + 1);
  y << problem.unknowns_from(z0, p, period), mu;
  Eigen::VectorXd along_parameter = Eigen::VectorXd::Zero(N + 1);
  along_parameter[N] = 1.0 / space.weights()[N];
  CorrectorOptions options;
  options.max_iterations = 20;
  return correct(problem, problem.section_through(z0, p), space, 0, options, y, along_parameter,
                 0.0, y, nullptr);
}

// An orbit only where there is one, in the corrector too (issue 33 item 5: find_periodic_orbit's
// rule, issue 32): a point closes to kOrbitClosure = 1e-7 of its amplitude besides the absolute
// tolerance. At the Hopf point itself (mu = 0: r' = -r^3, no cycle) Newton follows the decaying
// motion toward the equilibrium, r shrinking by 2/3 an iteration, its residual the decay over one
// period, r^3 2 pi: at the absolute tolerance alone (1e-9) it stopped at amplitude 3.9e-4, a
// residual of 1e-6 of it (measured before the rule), and called that an orbit. The rule takes it
// on to where the residual is 1e-7 of the amplitude (r^2 2 pi = 1e-7, r = 1.3e-4; measured:
// amplitude 1.2e-4, residual 1.0e-11): no closer to an orbit, only 3 times nearer the
// equilibrium, where a family's Hopf end ends it (Continuation::hopf_end). The rule cannot tell
// such a pseudo-orbit from a cycle of that size, and this test says only that much. Next to the
// Hopf point (mu = 1e-4) the genuine cycle r = sqrt(mu) = 0.01 corrects to its exact radius (to
// 1e-7: the radius is fixed only to the residual over 1 - exp(-4 pi mu), 800 times it; measured
// 1.6e-8) and period 2 pi (to 1e-8).
TEST(Corrector, AnOrbitClosesToItsAmplitude) {
  const Correction none = correct_at(0.0, 2e-3);
  if (none.converged) {
    const double amplitude = sampled_amplitude(none.evaluation.samples);
    EXPECT_LE(none.residual, kOrbitClosure * amplitude);
    EXPECT_LT(amplitude, 1.3e-4);
  }
  const Correction cycle = correct_at(1e-4, 0.0102);
  ASSERT_TRUE(cycle.converged) << cycle.reason;
  EXPECT_NEAR(cycle.y.head(2).norm(), 0.01, 1e-7);
  EXPECT_NEAR(cycle.y[2], 2 * std::numbers::pi, 1e-8);
  EXPECT_EQ(cycle.y[3], 1e-4);
}

}  // namespace
}  // namespace sympathy
