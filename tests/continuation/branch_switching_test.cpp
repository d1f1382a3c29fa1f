// Branch switching (continuation/branch_switching.hpp) on normal forms whose new branches are
// known in closed form (tests/support/test_systems.hpp): the transverse pitchfork of cycles
// (w = +-sqrt(mu) beyond mu = 0, the same circle) and the Moebius twist (the doubled orbit
// xi = +-sqrt(mu) of period 4 pi). Tolerance 1e-8: the orbits' accuracy at rtol 1e-11.
#include "sympathy/continuation/branch_switching.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::NormalForm;
using Kind = NormalForm::Kind;
using testing::kPi;

ContinuationOptions window(double lower, double upper) {
  ContinuationOptions o;
  o.lower = lower;
  o.upper = upper;
  return o;
}

PeriodicOrbit circle(const OdeSystem& system, const InvariantSubspace& subspace = {}) {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(system.dimension());
  z[0] = 1.0;
  const auto orbit = solve_periodic_orbit(system, system.default_parameters(), z, 2 * kPi, subspace,
                                          OrbitOptions{});
  EXPECT_TRUE(orbit.converged()) << orbit.newton.reason;
  return orbit;
}

const Bifurcation& only(const Branch& b, BifurcationType type) {
  const Bifurcation* found = nullptr;
  int count = 0;
  for (const auto& e : b.events)
    if (e.type == type) {
      found = &e;
      ++count;
    }
  EXPECT_EQ(count, 1) << b.stop_reason;
  if (!found) throw std::runtime_error("no such event");
  return *found;
}

// From the circle's BP at mu = 0, with and without the subspace w = 0 declared: the new branch
// has w^2 = mu on every point (both halves: w > 0 and w < 0, out to the window's edge), lies on
// the circle r = 1 with period 2 pi, starts at the event (point 0, within 1e-6 of it in the
// scaled norm: the event's own location error), leaves it along w, not along the old branch.
TEST(BranchSwitching, TransversePitchforkLandsOnTheBornBranch) {
  const NormalForm system(Kind::Pitchfork, -0.3);
  for (bool symmetric : {false, true}) {
    const InvariantSubspace subspace =
        symmetric ? InvariantSubspace(3, {{2, -1, 1.0}}, "w1 = 0") : InvariantSubspace();
    Continuation c(system, 0, window(-0.5, 0.5));
    const Branch old = c.run(circle(system, subspace), +1);
    const Bifurcation& bp = only(old, BifurcationType::BranchPoint);
    ASSERT_NEAR(bp.parameter, 0.0, 1e-8);
    EXPECT_EQ(bp.symmetry, symmetric ? SymmetryKind::Breaking : SymmetryKind::Unlabelled);
    SwitchStart start;
    const Branch born = switch_branch(system, old, bp, window(-0.5, 0.5), {}, &start);
    EXPECT_EQ(born.origin.rfind("BP at mu = ", 0), 0u) << born.origin;
    // The critical eigenvector is the transverse direction; the new tangent has no mu part.
    EXPECT_NEAR(std::abs(start.critical[2]), 1.0, 1e-6);
    EXPECT_LT(start.old_branch_component, 0.1);
    // Point 0 is the event; points 1 and -1 a step off it on either side.
    const auto zero = std::find_if(born.points.begin(), born.points.end(),
                                   [](const ContinuationPoint& p) { return p.index == 0; });
    ASSERT_NE(zero, born.points.end());
    EXPECT_LT(std::abs(zero->parameter - bp.parameter), 1e-12);
    EXPECT_LT((zero->orbit.state0 - bp.state0).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_EQ(born.points.front().index, -static_cast<int>(zero - born.points.begin()));
    for (std::size_t i = 1; i < born.points.size(); ++i)
      EXPECT_EQ(born.points[i].index, born.points[i - 1].index + 1);
    ASSERT_GE(born.points.size(), 6u) << born.stop_reason;
    int positive = 0, negative = 0;
    for (const auto& p : born.points) {
      const Eigen::VectorXd& z = p.orbit.state0;
      EXPECT_NEAR(z[2] * z[2], p.parameter, 1e-8) << "mu = " << p.parameter;
      EXPECT_NEAR(z.head(2).norm(), 1.0, 1e-8);
      EXPECT_NEAR(p.orbit.period, 2 * kPi, 1e-8);
      EXPECT_LT(p.orbit.floquet.trivial_error, 1e-8);
      EXPECT_GE(p.parameter, -1e-12);
      // Off w = 0 everywhere but at the event: not the branch it started on.
      if (p.index != 0) {
        EXPECT_GT(std::abs(z[2]), 1e-3) << "mu = " << p.parameter;
      }
      if (p.parameter > 1e-3) (z[2] > 0 ? positive : negative) += 1;
    }
    // Both halves, each out to the window's edge.
    EXPECT_GT(positive, 0);
    EXPECT_GT(negative, 0);
    EXPECT_EQ(born.stop, StopReason::ParameterBound) << born.stop_reason;
    EXPECT_EQ(born.backward_stop, StopReason::ParameterBound) << born.stop_reason;
    // The new orbits are stable (multiplier exp(-4 pi mu)).
    EXPECT_EQ(born.points.back().orbit.floquet.stability, Stability::Stable);
  }
}

// AUTO's lcbp (CrossingCircles): from the circle r = p2 = 2 continued in p1, its BP at p1 = 2
// (located on the regular branch-point system) is where the family r = p1 crosses it at an
// angle. Switching there lands on r = p1 (every point's radius its p1 to 1e-8, period 1), both
// ways out to the window, starting at the event (within 1e-6 of it); before the branching
// equation it stepped orthogonally to a tangent that was the other family's and followed r = 2
// again (this test then fails: the radius stays 2). With the CLI's default preset (Adams,
// augmented, rtol 5e-12): near the branch point the corrector's error is magnified by the
// Jacobian's small singular value (1.6e-8 at 0.03 from it with BDF at the library's rtol).
TEST(BranchSwitching, TranscriticalCrossingLandsOnTheOtherFamily) {
  const testing::CrossingCircles system(1.0, 2.0);
  ContinuationOptions o = window(1.0, 3.0);
  FlowOptions& f = o.orbit.shooting.flow;
  f.method = Method::Adams;
  f.nonlinear_solver = NonlinearSolver::FixedPoint;
  f.sensitivities = Sensitivities::Augmented;
  f.rtol = 5e-12;
  f.atol = 5e-14;
  Eigen::VectorXd z(2);
  z << 2.0, 0.0;
  const auto orbit =
      solve_periodic_orbit(system, system.default_parameters(), z, 1.0, {}, OrbitOptions{});
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  Continuation c(system, 0, o);
  const Branch old = c.run(orbit, +1);
  const Bifurcation& bp = only(old, BifurcationType::BranchPoint);
  ASSERT_NEAR(bp.parameter, 2.0, 1e-10);
  SwitchStart start;
  const Branch born = switch_branch(system, old, bp, o, {}, &start);
  EXPECT_LT(start.off_event, 0.1);
  const auto zero = std::find_if(born.points.begin(), born.points.end(),
                                 [](const ContinuationPoint& p) { return p.index == 0; });
  ASSERT_NE(zero, born.points.end());
  EXPECT_LT((zero->orbit.state0 - bp.state0).cwiseAbs().maxCoeff(), 1e-6);
  ASSERT_GE(born.points.size(), 6u) << born.stop_reason;
  int below = 0, above = 0;
  for (const auto& p : born.points) {
    EXPECT_NEAR(p.orbit.state0.norm(), p.parameter, 1e-8) << "p1 = " << p.parameter;
    EXPECT_NEAR(p.orbit.period, 1.0, 1e-8);
    if (p.parameter < 1.9) ++below;
    if (p.parameter > 2.1) ++above;
  }
  EXPECT_GT(below, 0);
  EXPECT_GT(above, 0);
  EXPECT_EQ(born.stop, StopReason::ParameterBound) << born.stop_reason;
  EXPECT_EQ(born.backward_stop, StopReason::ParameterBound) << born.stop_reason;
}

// From the circle's PD at mu = 0: the doubled orbit, of period 4 pi, with xi^2 = mu and eta = 0
// in the frame turning with theta / 2 (xi^2 + eta^2 from the transverse plane (a, w)).
TEST(BranchSwitching, MoebiusPeriodDoublingLandsOnTheDoubledOrbit) {
  const NormalForm system(Kind::Moebius, -0.3);
  Continuation c(system, 0, window(-0.5, 0.5));
  const Branch old = c.run(circle(system), +1);
  const Bifurcation& pd = only(old, BifurcationType::PeriodDoubling);
  ASSERT_NEAR(pd.parameter, 0.0, 1e-8);
  SwitchStart start;
  const Branch born = switch_branch(system, old, pd, window(-0.5, 0.5), {}, &start);
  EXPECT_NEAR(start.base.period, 4 * kPi, 1e-8);
  EXPECT_NE(born.origin.find("period doubled"), std::string::npos);
  ASSERT_GE(born.points.size(), 6u) << born.stop_reason;
  for (const auto& p : born.points) {
    const Eigen::VectorXd& z = p.orbit.state0;
    const double r = z.head(2).norm(), c2 = z[0] / r, s2 = z[1] / r, a = r - 1.0, w = z[2];
    const double xi_squared = a * a * 0.5 * (1.0 + c2) + a * w * s2 + w * w * 0.5 * (1.0 - c2);
    const double total = a * a + w * w;  // xi^2 + eta^2
    EXPECT_NEAR(p.orbit.period, 4 * kPi, 1e-8) << "mu = " << p.parameter;
    EXPECT_NEAR(xi_squared, p.parameter, 1e-8) << "mu = " << p.parameter;
    EXPECT_NEAR(total, xi_squared, 1e-8) << "mu = " << p.parameter;  // eta = 0
    EXPECT_GE(p.parameter, -1e-12);
  }
  EXPECT_EQ(born.stop, StopReason::ParameterBound) << born.stop_reason;
}

// Only a located BP or PD can be switched at; the message names what was given.
TEST(BranchSwitching, RefusesOtherEvents) {
  const NormalForm system(Kind::Rotation, -0.3);
  Continuation c(system, 0, window(-0.5, 0.5));
  const Branch old = c.run(circle(system), +1);
  const Bifurcation& ns = only(old, BifurcationType::NeimarkSacker);
  try {
    switch_branch(system, old, ns, window(-0.5, 0.5));
    FAIL() << "switched at an NS point";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("not at a Neimark-Sacker"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sympathy
