// Continuation of a periodically forced system (the period fixed by the forcing): the forced
// linear oscillator, whose periodic response is known in closed form all along the branch.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>

#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "tests/support/math.hpp"

namespace sympathy {
namespace {

using testing::kPi;

// x'' + c x' + k x = A cos(w t), states x and v = x'. Its periodic response (the only one: the
// system is linear and damped) is x = X cos(w t - phi) with X = A / sqrt((k - w^2)^2 + (c w)^2)
// and tan(phi) = c w / (k - w^2), phi in (0, pi): at t = 0, x = X cos(phi), v = X w sin(phi).
// Both multipliers over the period T = 2 pi / w have modulus exp(-c T / 2) (the roots
// -c/2 +- i sqrt(k - c^2/4) of the homogeneous equation, underdamped while k > c^2 / 4).
class ForcedOscillator final : public AutoDiffSystem<ForcedOscillator> {
 public:
  ForcedOscillator(double c, double k, double a, double w) {
    set_parameter_layout({{"c", {0}}, {"k", {1}}, {"A", {2}}, {"w", {3}}}, {c, k, a, w});
  }
  int dimension() const override { return 2; }
  bool autonomous() const override { return false; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double t, const T* z, const P* p, T* dz) const {
    using std::cos;
    dz[0] = z[1];
    dz[1] = -p[0] * z[1] - p[1] * z[0] + p[2] * cos(p[3] * t);
  }
};

// The same system declaring its forcing's period, 2 pi / w (OdeSystem::forcing_period).
class DeclaredForcing final : public AutoDiffSystem<DeclaredForcing> {
 public:
  DeclaredForcing(double c, double k, double a, double w) : oscillator_(c, k, a, w) {
    set_parameter_layout({{"c", {0}}, {"k", {1}}, {"A", {2}}, {"w", {3}}}, {c, k, a, w});
  }
  int dimension() const override { return 2; }
  bool autonomous() const override { return false; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  double forcing_period(const double* p) const override { return 2 * kPi / p[3]; }
  template <class T, class P>
  void evaluate(double t, const T* z, const P* p, T* dz) const {
    oscillator_.evaluate(t, z, p, dz);
  }

 private:
  ForcedOscillator oscillator_;
};

Eigen::Vector2d exact_state0(double c, double k, double a, double w) {
  const double amplitude = a / std::hypot(k - w * w, c * w);
  const double phi = std::atan2(c * w, k - w * w);
  return {amplitude * std::cos(phi), amplitude * w * std::sin(phi)};
}

// c = 0.1, A = 0.1, w = 1 (T = 2 pi), k from 0.5 through the resonance at k = w^2 = 1 (where
// X = A / (c w) = 1 and phi = pi / 2: the state (0, 1)) to 1.5, with a user point there. Every
// point's state is the exact response at its k to the integration's accuracy (1e-8 on states of
// order 0.1-1 at rtol 1e-11), its period 2 pi exactly (fixed), both multipliers of modulus
// exp(-0.1 pi) = 0.7304026910 to 1e-8; no bifurcation (a linear system has none), no trivial
// multiplier (a forced orbit has none).
TEST(ForcedBranch, LinearOscillatorThroughItsResonance) {
  const double c = 0.1, a = 0.1, w = 1.0;
  const ForcedOscillator system(c, 0.5, a, w);
  BranchProblem problem;
  problem.parameter = system.parameter_index("k");
  problem.values = system.default_parameters();
  problem.from = 0.5;
  problem.to = 1.5;
  problem.start_state = Eigen::Vector2d::Zero();  // Newton on a linear problem: one step
  problem.start_period = 2 * kPi / w;
  ContinuationOptions options;
  options.user_points = {1.0};
  const Branch branch = continue_branch(system, problem, options);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  EXPECT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
  ASSERT_GE(branch.points.size(), 10u);
  EXPECT_NEAR(branch.points.back().parameter, 1.5, 1e-12);
  const double modulus = std::exp(-c * kPi / w);
  for (const auto& p : branch.points) {
    SCOPED_TRACE("k = " + std::to_string(p.parameter));
    EXPECT_LT((p.orbit.state0 - exact_state0(c, p.parameter, a, w)).cwiseAbs().maxCoeff(), 1e-8);
    EXPECT_EQ(p.orbit.period, 2 * kPi / w);
    ASSERT_EQ(p.orbit.floquet.multipliers.size(), 2u);
    for (const auto& m : p.orbit.floquet.multipliers) {
      EXPECT_NEAR(std::abs(m.value), modulus, 1e-8);
      EXPECT_FALSE(m.trivial);
    }
  }
  ASSERT_EQ(branch.events.size(), 1u);
  const Bifurcation& uz = branch.events[0];
  EXPECT_EQ(uz.type, BifurcationType::UserPoint);
  EXPECT_NEAR(uz.parameter, 1.0, 1e-12);
  EXPECT_LT((uz.state0 - Eigen::Vector2d(0.0, 1.0)).cwiseAbs().maxCoeff(), 1e-8);
}

// The same with four shooting segments, each starting at its place in the forcing's period: the
// user point at the resonance is the same state.
TEST(ForcedBranch, MultipleShootingSegmentsStartAtTheirTimes) {
  const ForcedOscillator system(0.1, 0.5, 0.1, 1.0);
  BranchProblem problem;
  problem.parameter = 1;
  problem.values = system.default_parameters();
  problem.from = 0.5;
  problem.to = 1.5;
  problem.start_state = Eigen::Vector2d::Zero();
  problem.start_period = 2 * kPi;
  ContinuationOptions options;
  options.orbit.shooting.segments = 4;
  options.user_points = {1.0};
  const Branch branch = continue_branch(system, problem, options);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  ASSERT_EQ(branch.events.size(), 1u);
  EXPECT_LT((branch.events[0].state0 - Eigen::Vector2d(0.0, 1.0)).cwiseAbs().maxCoeff(), 1e-8);
  for (const auto& p : branch.points)
    EXPECT_LT((p.orbit.state0 - exact_state0(0.1, p.parameter, 0.1, 1.0)).cwiseAbs().maxCoeff(),
              1e-8);
}

// Without its period a forced system's branch is refused before any work, naming the field.
TEST(ForcedBranch, NeedsTheForcingPeriod) {
  const ForcedOscillator system(0.1, 0.5, 0.1, 1.0);
  BranchProblem problem;
  problem.parameter = 1;
  problem.values = system.default_parameters();
  problem.from = 0.5;
  problem.to = 1.5;
  problem.start_state = Eigen::Vector2d::Zero();
  EXPECT_NE(problem.problem_with(system).find("start_period: expected the forcing's period"),
            std::string::npos);
}

// A system that declares its forcing's period needs none given: find_periodic_orbit integrates
// the transient over whole forcing periods (60 s: 10 periods of 2 pi; the response is stable,
// |mu| = exp(-0.1 pi) per period, so it is approached to about 0.73^10 = 0.04 of the start's
// distance) and Newton converges to the exact response, to 1e-8; a branch runs from the start
// state alone.
TEST(ForcedBranch, DeclaredForcingPeriodNeedsNoPeriodGiven) {
  const DeclaredForcing system(0.1, 0.5, 0.1, 1.0);
  const ParameterValues p = system.default_parameters();
  const PeriodicOrbit orbit =
      find_periodic_orbit(system, p, Eigen::Vector2d(1.0, -1.0), InvariantSubspace(), {});
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_EQ(orbit.period, 2 * kPi);
  EXPECT_LT((orbit.state0 - exact_state0(0.1, 0.5, 0.1, 1.0)).cwiseAbs().maxCoeff(), 1e-8);

  BranchProblem problem;
  problem.parameter = 1;
  problem.values = p;
  problem.from = 0.5;
  problem.to = 0.8;
  problem.start_state = Eigen::Vector2d::Zero();
  EXPECT_EQ(problem.problem_with(system), "");
  const Branch branch = continue_branch(system, problem, {});
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  for (const auto& q : branch.points)
    EXPECT_LT((q.orbit.state0 - exact_state0(0.1, q.parameter, 0.1, 1.0)).cwiseAbs().maxCoeff(),
              1e-8);
}

// A branch keeps its start's period: a parameter the forcing's period depends on is refused
// before any work, and so is a period given that is not the forcing's.
TEST(ForcedBranch, ParameterThatMovesTheForcingPeriodIsRefused) {
  const DeclaredForcing system(0.1, 0.5, 0.1, 1.0);
  BranchProblem problem;
  problem.parameter = 3;  // w
  problem.values = system.default_parameters();
  problem.from = 1.0;
  problem.to = 1.5;
  problem.start_state = Eigen::Vector2d::Zero();
  EXPECT_NE(problem.problem_with(system).find("parameter w: the forcing's period depends on it"),
            std::string::npos)
      << problem.problem_with(system);
  problem.parameter = 1;  // k
  problem.from = 0.5;
  problem.to = 1.5;
  problem.start_period = 6.0;
  EXPECT_NE(problem.problem_with(system).find("start_period 6: expected the forcing's period"),
            std::string::npos)
      << problem.problem_with(system);
}

}  // namespace
}  // namespace sympathy
