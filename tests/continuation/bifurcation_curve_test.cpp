// Two-parameter curves (continuation/bifurcation_curve.hpp) on normal forms whose curves are
// known in closed form (tests/support/test_systems.hpp): with the second parameter a, the
// transverse growth rate is mu - a^2, so the BP, NS and PD curves are mu = a^2 exactly, and the
// fold form's LP curve is mu = -(1 + a)^2 / 4 with r^2 = (1 + a) / 2. Tolerance 1e-8: the orbits'
// and multipliers' accuracy at rtol 1e-11. And the test functions' algebra against exact
// eigenvalues.
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/stability_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include "continuation/curve_system.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/curve_test_function.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::NormalForm;
using Kind = NormalForm::Kind;
using testing::kPi;

// The exterior square's eigenvalues are the products of pairs: for a triangular B with diagonal
// 2, 3, 5, 7 they are 6, 10, 14, 15, 21, 35 exactly (to rounding).
TEST(CurveTestFunction, ExteriorSquareHasThePairProducts) {
  Eigen::MatrixXd b = Eigen::MatrixXd::Zero(4, 4);
  b.diagonal() << 2, 3, 5, 7;
  b(0, 1) = 0.3;
  b(1, 3) = -1.1;
  b(0, 2) = 0.7;
  // Similar to a triangular matrix: the same eigenvalues.
  std::mt19937 random(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd s(4, 4);
  for (int i = 0; i < 16; ++i) s(i) = u(random);
  s += 3 * Eigen::MatrixXd::Identity(4, 4);
  const Eigen::MatrixXd similar = s * b * s.inverse();
  Eigen::VectorXd mu = exterior_square(similar).eigenvalues().real();
  std::sort(mu.data(), mu.data() + mu.size());
  const double expected[] = {6, 10, 14, 15, 21, 35};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(mu[i], expected[i], 1e-10 * expected[i]);
}

// g vanishes where the matrix is singular and moves at -(w^T v) times the critical eigenvalue:
// A(t) = S diag(t, 1, 2) S^-1, g(t) ~ -(w^T v) t near t = 0 (w^T v from the solve at t = 0).
TEST(CurveTestFunction, BorderedValueIsRegularAtTheSingularity) {
  Eigen::MatrixXd s(3, 3);
  s << 2, 1, 0, 0.5, 1, 0.3, -0.2, 0.4, 1;
  const auto a = [&](double t) {
    return Eigen::MatrixXd(s * Eigen::Vector3d(t, 1, 2).asDiagonal() * s.inverse());
  };
  const BorderedSingularity test(a(0.01));
  EXPECT_NEAR(test.value(a(0.0)).g, 0.0, 1e-14);
  const double rate = test.value(a(0.0)).eigenvalue_rate();
  const double h = 1e-6;
  const double slope = (test.value(a(h)).g - test.value(a(-h)).g) / (2 * h);
  EXPECT_NEAR(std::abs(slope), rate, 1e-6 * rate);
}

struct Start {
  Branch branch;
  const Bifurcation* event = nullptr;
};

// The one-parameter branch in mu through the circle (r^2 = r2) from mu = from in `direction`,
// and its event of `type`.
Start branch_to(const NormalForm& system, double from, double lower, double upper, double r2,
                BifurcationType type, const InvariantSubspace& subspace = {}, int direction = +1) {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(system.dimension());
  z[0] = std::sqrt(r2);
  if (system.dimension() == 3) z[2] = 0.0;
  ParameterValues p = system.with_parameter(system.default_parameters(), 0, from);
  const auto orbit = solve_periodic_orbit(system, p, z, 2 * kPi, subspace, OrbitOptions{});
  EXPECT_TRUE(orbit.converged()) << orbit.newton.reason;
  ContinuationOptions o;
  o.lower = lower;
  o.upper = upper;
  Continuation c(system, 0, o);
  Start s;
  s.branch = c.run(orbit, direction);
  for (const auto& e : s.branch.events)
    if (e.type == type && !s.event) s.event = &e;
  return s;
}

CurveOptions window(double mu_lower, double mu_upper, double a_lower, double a_upper) {
  CurveOptions o;
  o.first_lower = mu_lower;
  o.first_upper = mu_upper;
  o.second_lower = a_lower;
  o.second_upper = a_upper;
  return o;
}

// BP of the transverse pitchfork, in (mu, a): mu = a^2 on every point, period 2 pi, the
// breaking multiplier 1; both halves out to the window's edges, the last points on them.
// The curve's measure of the integration's noise: the monodromy must map f(z0) onto f(z(T)).
// On the Hopf cycle with a transverse mode (HopfCycle) at z0 = (1, 0, 0), T = 2 pi, the exact
// monodromy is diag(exp(-4 pi), 1, exp(-2 pi a)) (radial, along the flow, transverse) and
// f(z0) = f(z(T)) = (0, 1, 0): no noise; a monodromy off by d in the column that f(z0) picks
// misses by exactly d. The integrated one misses by its integration error (below 1e-8 at rtol
// 1e-10 here), and the corrector's constants then stay those set for the default preset.
TEST(CurveSystem, NoiseIsTheMonodromysMissOnTheFlowDirection) {
  const testing::HopfCycle system(true, 0.5, 0.7);
  CurveOptions o;
  o.first_lower = 0.0;
  o.first_upper = 1.0;
  o.second_lower = 0.0;
  o.second_upper = 1.0;
  o.orbit.shooting.flow.rtol = 1e-10;
  o.orbit.shooting.flow.atol = 1e-12;
  detail::CurveSystem s(system, BifurcationType::BranchPoint, InvariantSubspace(),
                        detail::CriticalBlock::Shooting, 0, 1, system.default_parameters(), o);
  const double T = 2.0 * std::numbers::pi;
  const Eigen::VectorXd u = s.unknowns_of(Eigen::Vector3d(1.0, 0.0, 0.0), T, 0.5, 0.7);
  s.set_scales(u);
  s.set_section(u);
  detail::CurveSystem::Evaluation exact;
  exact.monodromy =
      Eigen::Vector3d(std::exp(-4.0 * std::numbers::pi), 1.0, std::exp(-T * 0.5)).asDiagonal();
  exact.end_rate = Eigen::Vector3d(0.0, 1.0, 0.0);
  s.measure_noise(u, exact);
  EXPECT_EQ(s.noise(), 0.0);
  detail::CurveSystem::Evaluation off = exact;
  off.monodromy(2, 1) = 3e-7;  // f(z0) = (0, 1, 0) picks column 1
  s.measure_noise(u, off);
  EXPECT_NEAR(s.noise(), 3e-7, 1e-22);
  const auto integrated = s.evaluate(u);
  ASSERT_TRUE(integrated.ok) << integrated.failure;
  s.measure_noise(u, integrated);
  EXPECT_GT(s.noise(), 0.0);
  EXPECT_LT(s.noise(), 1e-8);
}

TEST(BifurcationCurve, BranchPointCurveIsTheParabola) {
  const NormalForm system(Kind::Pitchfork, -0.3);
  const InvariantSubspace subspace(3, {{2, -1, 1.0}}, "w1 = 0");
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::BranchPoint, subspace);
  ASSERT_NE(s.event, nullptr);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 1, window(-1.0, 2.0, -0.8, 1.2));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  EXPECT_EQ(curve.stop, StopReason::ParameterBound) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 10u);
  for (const auto& p : curve.points) {
    EXPECT_NEAR(p.first, p.second * p.second, 1e-8) << "a = " << p.second;
    EXPECT_NEAR(p.period, 2 * kPi, 1e-8);
    ASSERT_EQ(p.critical.size(), 1u);
    EXPECT_NEAR(std::abs(p.critical[0] - 1.0), 0.0, 1e-8);
    EXPECT_LT(p.floquet.trivial_error, 1e-8);
    EXPECT_LT(p.uncertainty, 1e-7);
  }
  // Both ends on the window's edge: a = -0.8 and mu = 2 (a = sqrt 2) or a = 1.2.
  EXPECT_NEAR(curve.points.front().second, -0.8, 1e-12);
  EXPECT_NEAR(curve.points.back().second, 1.2, 1e-12);
  EXPECT_EQ(curve.origin.rfind("BP at mu = ", 0), 0u) << curve.origin;
  // The parabola turns back in mu at its vertex, (mu, a) = (0, 0) exactly: located there, mu to
  // 1e-10 (at a turn in mu its error is the square of the arclength's), a to 1e-6.
  int turns = 0;
  for (const auto& e : curve.events) {
    if (e.type != "turn in mu") continue;
    ++turns;
    EXPECT_TRUE(e.located) << e.note;
    EXPECT_NEAR(e.first, 0.0, 1e-10);
    EXPECT_NEAR(e.second, 0.0, 1e-6);
  }
  EXPECT_EQ(turns, 1);
}

// Another multiplier crossing the unit circle along a curve is located and named: on the BP
// curve mu = a^2 of the pitchfork beside s' = (a - 1/2) s, the s-multiplier exp(2 pi (a - 1/2))
// crosses +1 at a = 1/2 exactly (mu = 1/4), inside the subspace w = 0 (so named "LP").
TEST(BifurcationCurve, AnotherCrossingOnTheCurveIsLocated) {
  const NormalForm system(Kind::PitchforkAndGrowth, -0.3);
  const InvariantSubspace subspace(4, {{2, -1, 1.0}}, "w1 = 0");
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::BranchPoint, subspace);
  ASSERT_NE(s.event, nullptr);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 1, window(-1.0, 1.0, -0.2, 0.8));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  int found = 0;
  for (const auto& e : curve.events) {
    if (e.type.rfind("turn", 0) == 0) continue;
    EXPECT_EQ(e.type, "BP-LP");
    EXPECT_TRUE(e.located) << e.note;
    EXPECT_NEAR(e.second, 0.5, 1e-7);
    EXPECT_NEAR(e.first, 0.25, 1e-7);
    EXPECT_EQ(e.crossing_symmetry, SymmetryKind::Keeping);
    ++found;
  }
  EXPECT_EQ(found, 1);
}

// An NS curve whose pair shares its block with the trivial multiplier (no subspace declared):
// RotationAndGrowth's NS curve mu = a^2, along which the s-multiplier exp(2 pi (a - 1/2)) crosses
// +1 at (1/4, 1/2). The block's exterior square holds trivial x s = 1 there, a second zero of
// the matrix whose bordered value is the test function; the curve still passes it and locates
// the meeting from the NS side (an earlier note suspected that singularity of the in-phase
// (k, c) map's NS-LP point, where the orbit itself folds: this shows a crossing that is not a
// fold is not affected).
TEST(BifurcationCurve, NeimarkSackerCurveBesideTheTrivialMultiplierMeetsAnotherCrossing) {
  const NormalForm system(Kind::RotationAndGrowth, -0.3, 1, 0.0, 0.3);
  const Start s =
      branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::NeimarkSacker, InvariantSubspace());
  ASSERT_NE(s.event, nullptr);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 1, window(-0.5, 0.5, 0.0, 0.8));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 5u);
  for (const auto& p : curve.points) EXPECT_NEAR(p.first, p.second * p.second, 1e-8);
  EXPECT_EQ(curve.stop, StopReason::ParameterBound) << curve.stop_reason;
  int found = 0;
  for (const auto& e : curve.events) {
    if (e.type.rfind("turn", 0) == 0 || e.type[0] == 'R') continue;
    EXPECT_EQ(e.type, "NS-LP");
    EXPECT_TRUE(e.located) << e.note;
    EXPECT_NEAR(e.second, 0.5, 1e-7);
    EXPECT_NEAR(e.first, 0.25, 1e-7);
    ++found;
  }
  EXPECT_EQ(found, 1);
}

// NS of the rotation form in (mu, omega): the curve is mu = 0 for every omega (a = 0), and the
// rotation number is omega; the strong resonances 1:4 and 1:3 at omega = 1/4 and 1/3, located.
TEST(BifurcationCurve, NeimarkSackerCurveAndItsResonances) {
  const NormalForm system(Kind::Rotation, -0.3);
  const InvariantSubspace subspace(4, {{2, -1, 1.0}, {3, -1, 1.0}}, "u = 0, v = 0");
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::NeimarkSacker, subspace);
  ASSERT_NE(s.event, nullptr);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 2, window(-0.5, 0.5, 0.2, 0.45));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 5u);
  for (const auto& p : curve.points) {
    EXPECT_NEAR(p.first, 0.0, 1e-8) << "omega = " << p.second;
    EXPECT_NEAR(p.rotation, p.second, 1e-8);
    EXPECT_FALSE(p.neutral_saddle);
  }
  EXPECT_NEAR(curve.points.front().second, 0.2, 1e-12);
  EXPECT_NEAR(curve.points.back().second, 0.45, 1e-12);
  int found = 0;
  for (const auto& e : curve.events) {
    if (e.type == "R4") {
      EXPECT_NEAR(e.second, 0.25, 1e-7);
      ++found;
    }
    if (e.type == "R3") {
      EXPECT_NEAR(e.second, 1.0 / 3.0, 1e-7);
      ++found;
    }
    EXPECT_TRUE(e.located) << e.type << " " << e.note;
  }
  EXPECT_EQ(found, 2);
}

// At a 1:1 resonance the NS pair of the resonance form meets at +1 ((mu, omega) = (0, 0)) and
// turns real, exp(2 pi (mu +- sqrt(-omega))): one of them at +1 on omega = -mu^2, a BP curve
// through the resonance (the pair breaks u = v = 0). The map follows it from the resonance,
// which is its start, not a meeting on it: the other multiplier of the pair leaves +1 there too,
// and was reported as a "BP-BP" point at the curve's own start (the row setup's (k, c) map, 7e-9
// from its R1 origin).
TEST(BifurcationCurve, BranchPointCurveFromAOneToOneResonance) {
  const NormalForm system(Kind::Resonance, -0.3, 1, 0.0, 0.09);
  const InvariantSubspace subspace(4, {{2, -1, 1.0}, {3, -1, 1.0}}, "u = 0, v = 0");
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::NeimarkSacker, subspace);
  ASSERT_NE(s.event, nullptr);
  EXPECT_NEAR(s.event->parameter, 0.0, 1e-8);
  const auto curves = event_curves(system, s.branch, 2, window(-0.5, 0.5, -0.2, 0.2));
  const BifurcationCurve* ns = nullptr;
  const BifurcationCurve* bp = nullptr;
  for (const auto& c : curves) {
    if (c.kind == BifurcationType::NeimarkSacker) ns = &c;
    if (c.kind == BifurcationType::BranchPoint) bp = &c;
  }
  ASSERT_NE(ns, nullptr);
  ASSERT_NE(bp, nullptr);
  int resonances = 0;
  for (const auto& e : ns->events)
    if (e.type == "R1") {
      ++resonances;
      EXPECT_TRUE(e.located) << e.note;
      EXPECT_NEAR(e.first, 0.0, 1e-7);
      EXPECT_NEAR(e.second, 0.0, 1e-7);
    }
  EXPECT_EQ(resonances, 1);
  ASSERT_TRUE(bp->started()) << bp->stop_reason;
  EXPECT_EQ(bp->origin.rfind("R1 point at mu = ", 0), 0u) << bp->origin;
  ASSERT_GE(bp->points.size(), 10u);
  for (const auto& p : bp->points) {
    EXPECT_NEAR(p.second, -p.first * p.first, 1e-8) << "mu = " << p.first;
    // The start is the R1 point as located (to 1e-9 in arclength): at omega > 0 beside it the
    // pair is exp(+-i T sqrt(omega)), not yet real: |mu - 1| = T sqrt(omega) there (T = 2 pi).
    const double beside =
        p.index == 0 ? 2 * std::numbers::pi * std::sqrt(std::max(p.second, 0.0)) : 0.0;
    EXPECT_NEAR(std::abs(p.critical[0] - 1.0), 0.0, 1e-8 + 1.01 * beside)
        << "index " << p.index << ", mu = " << p.first << ", omega = " << p.second;
  }
  // Both halves, mu < 0 and mu > 0, out to omega = -0.2.
  EXPECT_NEAR(bp->points.front().second, -0.2, 1e-12);
  EXPECT_NEAR(bp->points.back().second, -0.2, 1e-12);
  EXPECT_LT(bp->points.front().first * bp->points.back().first, 0.0);
  for (const auto& e : bp->events)
    EXPECT_EQ(e.type.find('-'), std::string::npos)
        << e.type << " at " << e.first << ", " << e.second << ": a meeting at the curve's start";
}

// PD of the Moebius twist in (mu, a): mu = a^2, the critical multiplier -1.
TEST(BifurcationCurve, PeriodDoublingCurveIsTheParabola) {
  const NormalForm system(Kind::Moebius, -0.3);
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::PeriodDoubling);
  ASSERT_NE(s.event, nullptr);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 1, window(-1.0, 1.0, -0.6, 0.7));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 8u);
  for (const auto& p : curve.points) {
    EXPECT_NEAR(p.first, p.second * p.second, 1e-8) << "a = " << p.second;
    EXPECT_NEAR(std::abs(p.critical[0] + 1.0), 0.0, 1e-8);
  }
}

// The same PD curve on an orbit that rotates (theta an angle state gaining 2 pi a period): the
// curve's shooting residual must take the winding off (issue 33, class 5: AUTO's pen, whose PD
// curve did not start: "the chord diverged").
TEST(BifurcationCurve, PeriodDoublingCurveOfARotatingOrbitIsTheParabola) {
  const NormalForm system(NormalForm::Kind::RotatingMoebius, -0.3);
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::PeriodDoubling);
  ASSERT_NE(s.event, nullptr);
  EXPECT_NEAR(s.event->parameter, 0.0, 1e-8);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 1, window(-1.0, 1.0, -0.6, 0.7));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 8u) << curve.stop_reason;
  for (const auto& p : curve.points) {
    EXPECT_NEAR(p.first, p.second * p.second, 1e-8) << "a = " << p.second;
    EXPECT_NEAR(std::abs(p.critical[0] + 1.0), 0.0, 1e-8);
    EXPECT_NEAR(p.period, 2 * kPi, 1e-8);
  }
  EXPECT_NEAR(curve.points.front().second, -0.6, 1e-12);
  EXPECT_NEAR(curve.points.back().second, 0.7, 1e-12);
}

// LP of the fold form in (mu, a): mu = -(1 + a)^2 / 4 with the orbit at r^2 = (1 + a) / 2, the
// fold's Jordan partner of the trivial multiplier at 1 (to the square root of the error).
TEST(BifurcationCurve, FoldCurveIsTheParabola) {
  const NormalForm system(Kind::Fold, -0.2);
  const Start s = branch_to(system, -0.2, -0.5, 0.5, 0.7236, BifurcationType::Fold, {}, -1);
  ASSERT_NE(s.event, nullptr);
  const BifurcationCurve curve =
      continue_curve(system, s.branch, *s.event, 1, window(-1.0, 0.0, -0.5, 0.5));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  ASSERT_GE(curve.points.size(), 8u);
  for (const auto& p : curve.points) {
    const double b = 1.0 + p.second;
    EXPECT_NEAR(p.first, -b * b / 4.0, 1e-8) << "a = " << p.second;
    EXPECT_NEAR(p.state0.head(2).squaredNorm(), b / 2.0, 1e-7) << "a = " << p.second;
    EXPECT_NEAR(p.period, 2 * kPi, 1e-8);
  }
}

// Whether a curve passes through a point (what a map asks before following an event's curve),
// on the points of mu = a^2 at a = 0, 0.1, ..., 1 (rotation 0.2 + a / 10): through (0.25, 0.5)
// and (0.4225, 0.65) between points (within 1e-4, the chord's error there 2.5e-3 is within half
// the points' distance in mu, 0.065); not through (0.32, 0.5) (0.07 off, beyond half the
// distance, 0.055) nor beyond its ends; with a
// rotation, only where it matches within 2e-3.
TEST(BifurcationCurve, PassesThroughPointsOnItOnly) {
  BifurcationCurve curve;
  for (int i = 0; i <= 10; ++i) {
    CurvePoint p;
    p.second = 0.1 * i;
    p.first = p.second * p.second;
    p.rotation = 0.2 + p.second / 10.0;
    curve.points.push_back(p);
  }
  EXPECT_TRUE(curve_passes_through(curve, 0.25, 0.5));
  EXPECT_TRUE(curve_passes_through(curve, 0.4225, 0.65));
  EXPECT_FALSE(curve_passes_through(curve, 0.32, 0.5));
  EXPECT_FALSE(curve_passes_through(curve, 1.21, 1.1));
  EXPECT_TRUE(curve_passes_through(curve, 0.25, 0.5, 0.25));
  EXPECT_TRUE(curve_passes_through(curve, 0.25, 0.5, 0.2515));
  EXPECT_FALSE(curve_passes_through(curve, 0.25, 0.5, 0.2525));
}

// Bad requests are refused before any work, saying what was expected.
TEST(BifurcationCurve, RefusesWhatItCannotFollow) {
  const NormalForm system(Kind::Pitchfork, -0.3);
  const Start s = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::BranchPoint);
  ASSERT_NE(s.event, nullptr);
  const auto message = [&](int second, const CurveOptions& o) {
    try {
      continue_curve(system, s.branch, *s.event, second, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  // No subspace declared: the BP breaks no symmetry the curve could keep.
  EXPECT_NE(message(1, window(-1, 1, -1, 1)).find("breaks no declared symmetry"),
            std::string::npos);
  const InvariantSubspace subspace(3, {{2, -1, 1.0}}, "w1 = 0");
  const Start t = branch_to(system, -0.3, -0.5, 0.5, 1.0, BifurcationType::BranchPoint, subspace);
  ASSERT_NE(t.event, nullptr);
  const auto message2 = [&](int second, const CurveOptions& o) {
    try {
      continue_curve(system, t.branch, *t.event, second, o);
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message2(0, window(-1, 1, -1, 1)).find("the branch's own"), std::string::npos);
  EXPECT_NE(message2(1, window(0.5, 1, -1, 1)).find("does not contain the event"),
            std::string::npos);
  EXPECT_NE(message2(1, window(1, -1, -1, 1)).find("first window"), std::string::npos);
}

}  // namespace
}  // namespace sympathy
