#include "sympathy/continuation/continuation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/continuation/predictor.hpp"

#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::NormalForm;
using Kind = NormalForm::Kind;
using testing::kPi;

ContinuationOptions options(double lower, double upper) {
  ContinuationOptions o;
  o.lower = lower;
  o.upper = upper;
  o.orbit.shooting.flow.rtol = 1e-11;
  o.orbit.shooting.flow.atol = 1e-13;
  return o;
}

// The unit circle (with zero transverse states) as the starting orbit.
PeriodicOrbit circle(const OdeSystem& system, double radius = 1.0) {
  Eigen::VectorXd z = Eigen::VectorXd::Zero(system.dimension());
  z[0] = radius;
  const auto orbit =
      solve_periodic_orbit(system, system.default_parameters(), z, 2 * kPi, {}, OrbitOptions{});
  EXPECT_TRUE(orbit.converged()) << orbit.newton.reason;
  return orbit;
}

std::vector<Bifurcation> events_of(const Branch& b, BifurcationType type) {
  std::vector<Bifurcation> out;
  for (const auto& e : b.events)
    if (e.type == type) out.push_back(e);
  return out;
}

// Fold of cycles at mu = -1/4 exactly (r^2 = 1/2), reached from the stable cycle near r = 1
// going down; the branch turns back there (and would reach r = 0, the Hopf point, at mu = 0:
// the upper bound stops it before). Located to 1e-8.
TEST(Continuation, FoldOfCyclesLocated) {
  NormalForm system(Kind::Fold, -0.05);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, -0.02));
  Branch branch = c.run(start, -1);
  const auto folds = events_of(branch, BifurcationType::Fold);
  ASSERT_EQ(folds.size(), 1u) << branch.stop_reason;
  EXPECT_NEAR(folds[0].parameter, -0.25, 1e-8);
  EXPECT_TRUE(folds[0].located());
  EXPECT_TRUE(folds[0].trusted());
  EXPECT_NEAR(folds[0].state0.head(2).norm(), std::sqrt(0.5), 1e-4);
  EXPECT_NEAR(folds[0].period, 2 * kPi, 1e-9);
  // Before the fold stable, after it (the inner cycles) unstable.
  EXPECT_EQ(branch.points.front().orbit.floquet.stability, Stability::Stable);
  bool unstable_after = false;
  for (const auto& p : branch.points)
    if (p.orbit.state0.head(2).norm() < 0.6)
      unstable_after |= p.orbit.floquet.stability == Stability::Unstable;
  EXPECT_TRUE(unstable_after);
  EXPECT_TRUE(events_of(branch, BifurcationType::BranchPoint).empty());
}

// States of order 300: the attainable residual grows with the state (the integration's error is
// relative, about 20 rtol |z|), so the orbit and the branch converge at the defaults (with an
// absolute 1e-9 a converged start was refused: "corrector diverged, residual 1.1e-8"). Exact:
// r = 300 sqrt(1 + mu), period 2 pi.
TEST(Continuation, LargeStatesConvergeAtTheDefaults) {
  testing::ScaledCircle system(300.0);
  const auto start = solve_periodic_orbit(system, system.default_parameters(),
                                          Eigen::Vector2d(301.0, 0.0), 2 * kPi, {}, OrbitOptions{});
  ASSERT_TRUE(start.converged()) << start.newton.reason;
  EXPECT_NEAR(start.state0.norm(), 300.0, 1e-6 * 300.0);
  ContinuationOptions o;
  o.lower = 0.0;
  o.upper = 0.5;
  Continuation c(system, 0, o);
  const Branch branch = c.run(start, +1);
  ASSERT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
  for (const auto& p : branch.points) {
    EXPECT_NEAR(p.orbit.state0.norm(), 300.0 * std::sqrt(1.0 + p.parameter), 1e-6 * 300.0);
    EXPECT_NEAR(p.orbit.period, 2 * kPi, 1e-8);
  }
}

// The generic fold of cycles: the period changes along the family (theta' = 1 + r^2), so at the
// fold the multiplier 1 is a Jordan block, whose eigenvalues split like the square root of the
// monodromy's error. The trivial multiplier measured on f (the compression of the monodromy onto
// the flow direction, first-order accurate) keeps the fold trusted; located at mu = -1/4 exactly,
// period 2 pi / (1 + 1/2).
TEST(Continuation, GenericFoldOfCyclesTrusted) {
  NormalForm system(Kind::ShearedFold, -0.05, 1, 0.0, 1.0);
  Eigen::Vector2d z(1.0, 0.0);
  const auto start =
      solve_periodic_orbit(system, system.default_parameters(), z, kPi, {}, OrbitOptions{});
  ASSERT_TRUE(start.converged()) << start.newton.reason;
  Continuation c(system, 0, options(-0.5, -0.02));
  Branch branch = c.run(start, -1);
  const auto folds = events_of(branch, BifurcationType::Fold);
  ASSERT_EQ(folds.size(), 1u) << branch.stop_reason;
  EXPECT_NEAR(folds[0].parameter, -0.25, 1e-8);
  EXPECT_NEAR(folds[0].period, 2 * kPi / 1.5, 1e-8);
  EXPECT_TRUE(folds[0].trusted()) << folds[0].note;
  EXPECT_LT(folds[0].floquet.trivial_error, 1e-8);
}

// Past the fold the inner cycles (r^2 from 1/2 down to 0) shrink into the equilibrium r = 0 at
// mu = 0, the Hopf point, where the orbit vanishes. There the tangent turns with no multiplier
// at +1 (a fold of cycles has one): the branch ends there, at the equilibrium's Hopf point
// located on the equilibria (mu = 0 exactly, period 2 pi), the turn not reported as a fold, rather
// than retrace itself back through the fold (the reliability issue's "a fold where the orbit
// vanishes, then 40 points back up").
TEST(Continuation, BranchShrinkingIntoAnEquilibriumEndsThere) {
  NormalForm system(Kind::Fold, -0.05);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  const Branch branch = c.run(start, -1);
  ASSERT_EQ(branch.stop, StopReason::HopfPoint) << branch.stop_reason;
  ASSERT_TRUE(branch.hopf_end.has_value());
  EXPECT_NEAR(branch.hopf_end->parameter, 0.0, 1e-10);
  EXPECT_NEAR(branch.hopf_end->period, 2 * kPi, 1e-9);
  const auto folds = events_of(branch, BifurcationType::Fold);
  ASSERT_EQ(folds.size(), 1u);
  EXPECT_NEAR(folds[0].parameter, -0.25, 1e-8);
  EXPECT_TRUE(folds[0].trusted());
  for (const auto& e : branch.events) EXPECT_NE(e.trust, EventTrust::NoCrossingMultiplier);
  // The last orbits are small (r^2 = mu + r^4 ~ |mu|), and none retraces the outer ones.
  EXPECT_LT(branch.points.back().orbit.state0.head(2).norm(), 0.05);
  for (std::size_t i = 1; i < branch.points.size(); ++i)
    if (branch.points[i].orbit.state0.head(2).norm() < std::sqrt(0.5)) {
      for (std::size_t j = i; j < branch.points.size(); ++j)
        EXPECT_LT(branch.points[j].orbit.state0.head(2).norm(), std::sqrt(0.5) + 1e-6) << j;
      break;
    }
}

// The cubic predictor and the chord steps on plain integrations save integrations with
// sensitivities (the expensive ones) and change no result: the same fold at mu = -1/4 (exact)
// to 1e-8 either way, with fewer Newton iterations per point with them than with the tangent
// predictor and Newton alone.
TEST(Continuation, CurvedPredictorAndChordStepsSaveWork) {
  auto run = [](bool curved, int chord_steps) {
    NormalForm system(Kind::Fold, -0.05);
    const auto start = circle(system);
    auto o = options(-0.5, -0.02);
    o.curved_predictor = curved;
    o.max_chord_steps = chord_steps;
    Continuation c(system, 0, o);
    return c.run(start, -1);
  };
  const Branch plain = run(false, 0), fast = run(true, 6);
  auto per_point = [](const Branch& b) {
    int it = 0;
    for (const auto& p : b.points) it += p.iterations;
    return static_cast<double>(it) / static_cast<double>(b.points.size());
  };
  for (const Branch* b : {&plain, &fast}) {
    const auto folds = events_of(*b, BifurcationType::Fold);
    ASSERT_EQ(folds.size(), 1u) << b->stop_reason;
    EXPECT_NEAR(folds[0].parameter, -0.25, 1e-8);
  }
  EXPECT_LT(per_point(fast), per_point(plain));  // measured: 1.17 against 2.5
}

// How far a step turned the branch is measured in the orbit's own unknowns (z_0 without its shift
// along f, T, p): on two segments, tangents that differ only in the second segment's start, or by
// a shift along f(z_0), have turned by nothing (cosine 1, where the whole vectors' is 0.5 or
// less), and a turn in (z_0, T) by an angle alpha has cosine cos(alpha), exactly.
TEST(Continuation, TurnIsMeasuredInTheOrbitsOwnUnknowns) {
  NormalForm system(Kind::Fold, -0.05);
  ShootingOptions shooting;
  shooting.segments = 2;
  ShootingProblem problem(system, shooting);
  BranchSpace space(system, problem, 0, system.default_parameters(), 2.0, 1e-10);
  const int n = system.dimension();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  z[0] = 1.0;
  space.reset_scales(z, 2 * kPi, FlowOptions{});
  const int N = space.unknowns();
  ASSERT_EQ(N, 2 * n + 1);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(N + 1);
  y.head(n) = z;
  y.segment(n, n) = -z;  // half a turn on
  y[N - 1] = 2 * kPi;
  y[N] = -0.05;
  auto unit = [&](Eigen::VectorXd e) { return Eigen::VectorXd(e / std::sqrt(space.dot(e, e))); };
  auto basis = [&](int i) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(N + 1);
    e[i] = 1.0;
    return unit(e);
  };
  const Eigen::VectorXd period = basis(N - 1), second = basis(n + 1);
  Eigen::VectorXd shift = Eigen::VectorXd::Zero(N + 1);
  shift.head(n) = system.rhs(0.0, z, system.default_parameters());
  shift = unit(shift);
  // A change of z_0 across f there.
  const Eigen::VectorXd radial = unit(basis(0) - space.dot(basis(0), shift) * shift);
  const Eigen::VectorXd u = unit(radial + period);
  const Eigen::VectorXd v = unit(radial + period + 2.0 * second + 3.0 * shift);
  EXPECT_NEAR(space.turn_cosine(u, v, y), 1.0, 1e-12);
  EXPECT_LT(space.dot(u, v), 0.5);
  for (double alpha : {0.1, 0.7, 2.0}) {
    const Eigen::VectorXd w = std::cos(alpha) * radial + std::sin(alpha) * period;
    EXPECT_NEAR(space.turn_cosine(radial, w + second, y), std::cos(alpha), 1e-12) << alpha;
  }
}

// Location's guess inside a step (predict_between) against an exact curve: on a circle of
// radius R in the branch's scaled norm, a at angle 0 and b at angle h / R, the point whose
// arclength along a's tangent is s lies at angle asin(s / R). The cubic through a and b with
// their tangents finds it to O(h^4): measured 1.2e-5 R at h = 0.2 R (bound 2e-5 R; Hermite
// interpolation's h^4 / 384 |Y''''| is 4e-6 R with |Y''''| = 1 / R^3, the rest from the chord
// standing in for the arclength), and 16.1 times smaller at half the step (bound 16 +- 4), where
// a's tangent alone is off by about s^2 / 2R (7e-3 R here, over 300 times more); points in
// different sections get no guess.
TEST(Continuation, GuessInsideAStepIsFourthOrder) {
  NormalForm system(Kind::Fold, -0.05);
  ShootingProblem problem(system, ShootingOptions{});
  BranchSpace space(system, problem, 0, system.default_parameters(), 2.0, 1e-10);
  Eigen::VectorXd z = Eigen::VectorXd::Zero(system.dimension());
  z[0] = 1.0;
  space.reset_scales(z, 2 * kPi, FlowOptions{});
  const int N = space.unknowns();
  auto unit = [&](int i) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(N + 1);
    e[i] = 1.0;
    return Eigen::VectorXd(e / std::sqrt(space.dot(e, e)));
  };
  const Eigen::VectorXd e1 = unit(0), e2 = unit(N);  // orthonormal in the scaled norm
  ASSERT_NEAR(space.dot(e1, e2), 0.0, 1e-15);
  const double R = 0.5;
  Eigen::VectorXd centre = Eigen::VectorXd::Zero(N + 1);
  centre[0] = 1.0;
  centre[N] = -0.1;
  auto at = [&](double angle) {
    ContinuationPoint p;
    const Eigen::VectorXd y = centre + R * (std::cos(angle) * e1 + std::sin(angle) * e2);
    p.unknowns = y.head(N);
    p.parameter = y[N];
    p.tangent = -std::sin(angle) * e1 + std::cos(angle) * e2;
    p.section = {Eigen::VectorXd::Ones(N), Eigen::VectorXd::Ones(N)};
    return p;
  };
  auto error = [&](double h, double* straight) {
    const ContinuationPoint a = at(0.0), b = at(h / R);
    const double s = 0.6 * R * std::sin(h / R);
    const auto guess = predict_between(space, a, b, s, 0.9);
    EXPECT_TRUE(guess.has_value());
    if (!guess) return 1.0;
    const double angle = std::asin(s / R);
    const Eigen::VectorXd exact = centre + R * (std::cos(angle) * e1 + std::sin(angle) * e2);
    Eigen::VectorXd ya(N + 1);
    ya << a.unknowns, a.parameter;
    const Eigen::VectorXd off = guess->y - exact, line = ya + s * a.tangent - exact;
    if (straight) *straight = std::sqrt(space.dot(line, line));
    EXPECT_GT(guess->fraction, 0.0);
    EXPECT_LT(guess->fraction, 1.0);
    return std::sqrt(space.dot(off, off));
  };
  double straight = 0.0;
  const double coarse = error(0.2 * R, &straight), fine = error(0.1 * R, nullptr);
  EXPECT_LT(coarse, 2e-5 * R);
  EXPECT_GT(straight, 300.0 * coarse);
  EXPECT_NEAR(coarse / fine, 16.0, 4.0);
  ContinuationPoint a = at(0.0), b = at(0.1);
  b.section.through[0] = 2.0;
  EXPECT_FALSE(predict_between(space, a, b, 0.01, 0.9).has_value());
}

// The last point lies on the bound, exactly, and no point beyond it (the reliability issue: a
// branch used to end a full step past --to), both ways; the point on the bound is an orbit of
// the normal form there (radius 1 whatever mu for the pitchfork family: residual below 1e-8), and
// costs one integration more than the branch stopped a point before it.
TEST(Continuation, LastPointLiesOnTheBound) {
  NormalForm system(Kind::Pitchfork, -0.4);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  for (int direction : {+1, -1}) {
    const Branch branch = c.run(start, direction);
    ASSERT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
    for (const auto& p : branch.points) {
      EXPECT_GE(p.parameter, -0.5);
      EXPECT_LE(p.parameter, 0.5);
    }
    EXPECT_EQ(branch.points.back().parameter, direction > 0 ? 0.5 : -0.5);
    EXPECT_LT(branch.points.back().orbit.residual, 1e-8);
    ContinuationOptions shorter = options(-0.5, 0.5);
    shorter.max_points = static_cast<int>(branch.points.size()) - 1;
    const Branch before = Continuation(system, 0, shorter).run(start, direction);
    ASSERT_EQ(before.stop, StopReason::PointLimit);
    // The last step's prediction passed the bound: the point on the bound came from it at once,
    // one integration (its prediction lands: radius 1 at every mu), not the step's point beyond
    // the bound and then the bound's (two).
    EXPECT_EQ(branch.points.back().iterations, 0);
    EXPECT_EQ(branch.flow.calls - before.flow.calls, 1);
  }
}

// A transverse pitchfork: the multiplier exp(2 pi mu) crosses +1 at mu = 0 without a fold.
TEST(Continuation, BranchPointLocated) {
  NormalForm system(Kind::Pitchfork, -0.4);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  const Branch branch = c.run(start, +1);
  const auto bps = events_of(branch, BifurcationType::BranchPoint);
  ASSERT_EQ(bps.size(), 1u) << branch.stop_reason;
  EXPECT_NEAR(bps[0].parameter, 0.0, 1e-8);
  EXPECT_EQ(bps[0].multiplicity, 1);
  // No subspace declared: located on the regular branch-point system (a pitchfork of cycles is a
  // simple branch point too: the branches w = 0 and mu = w^2 cross transversally).
  EXPECT_NE(bps[0].note.find("regular BP system"), std::string::npos) << bps[0].note;
  EXPECT_LE(std::abs(bps[0].parameter), bps[0].uncertainty);
  EXPECT_TRUE(events_of(branch, BifurcationType::Fold).empty());
  EXPECT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
  // Multipliers along the branch: exp(2 pi mu), to the integration accuracy.
  for (const auto& p : branch.points) {
    double largest = 0.0;
    for (const auto& m : p.orbit.floquet.multipliers)
      if (!m.trivial) largest = std::max(largest, m.modulus());
    EXPECT_NEAR(largest, std::exp(2 * kPi * p.parameter), 1e-8) << p.parameter;
  }
}

// Two transverse directions cross +1 together (a symmetric system): the product of
// (mu_i - 1) keeps its sign and would miss it; the event says multiplicity 2.
TEST(Continuation, DoubleCrossingReported) {
  NormalForm system(Kind::Pitchfork, -0.4, 2);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  const Branch branch = c.run(start, +1);
  const auto bps = events_of(branch, BifurcationType::BranchPoint);
  ASSERT_EQ(bps.size(), 1u);
  EXPECT_EQ(bps[0].multiplicity, 2);
  EXPECT_NEAR(bps[0].parameter, 0.0, 1e-8);
  EXPECT_NE(bps[0].note.find("2 multipliers cross +1 together"), std::string::npos);
}

// A complex pair exp(2 pi (mu +- 0.3 i)) leaves the unit circle at mu = 0: Neimark-Sacker,
// with the pair's argument 2 pi 0.3 (mod 2 pi) at the located point.
TEST(Continuation, NeimarkSackerLocated) {
  NormalForm system(Kind::Rotation, -0.3);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  const Branch branch = c.run(start, +1);
  const auto ns = events_of(branch, BifurcationType::NeimarkSacker);
  ASSERT_EQ(ns.size(), 1u) << branch.stop_reason;
  EXPECT_NEAR(ns[0].parameter, 0.0, 1e-8);
  double angle = 0.0;
  for (const auto& m : ns[0].floquet.multipliers)
    if (!m.trivial) angle = std::max(angle, std::abs(std::arg(m.value)));
  EXPECT_NEAR(angle, 2 * kPi * 0.3, 1e-6);
  EXPECT_TRUE(events_of(branch, BifurcationType::BranchPoint).empty());
}

// The reported uncertainty of a crossing: the bracket plus the multipliers' error over the
// crossing speed. On the Moebius band the crossing multiplier is -exp(2 pi mu), whose |mu| - 1
// moves at 2 pi per unit of mu at the crossing; the speed is taken over the step that found it
// (a few hundredths of mu wide), so within 10% of 2 pi. The error is the located orbit's trivial
// one. (Branch points off a symmetric subspace are located on their regular system instead:
// branch_point_test.cpp.)
TEST(Continuation, UncertaintyIsBracketPlusErrorOverCrossingSpeed) {
  NormalForm system(Kind::Moebius, -0.3);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  const Branch branch = c.run(start, +1);
  const auto pds = events_of(branch, BifurcationType::PeriodDoubling);
  ASSERT_EQ(pds.size(), 1u);
  const Bifurcation& pd = pds[0];
  EXPECT_GT(pd.floquet.trivial_error, 0.0);
  const double implied_speed = pd.floquet.trivial_error / (pd.uncertainty - pd.bracket);
  EXPECT_NEAR(implied_speed, 2 * kPi, 0.1 * 2 * kPi);
  EXPECT_LE(pd.bracket, 1e-8);
}

// A real multiplier -exp(2 pi mu) crosses -1 at mu = 0: period doubling.
TEST(Continuation, PeriodDoublingLocated) {
  NormalForm system(Kind::Moebius, -0.3);
  const auto start = circle(system);
  EXPECT_NEAR(start.floquet.multipliers[1].value.real(), -std::exp(-0.6 * kPi), 1e-8);
  Continuation c(system, 0, options(-0.5, 0.5));
  const Branch branch = c.run(start, +1);
  const auto pd = events_of(branch, BifurcationType::PeriodDoubling);
  ASSERT_EQ(pd.size(), 1u) << branch.stop_reason;
  EXPECT_NEAR(pd[0].parameter, 0.0, 1e-8);
  EXPECT_EQ(pd[0].multiplicity, 1);
  EXPECT_TRUE(events_of(branch, BifurcationType::NeimarkSacker).empty());
}

// A complex pair that meets on the negative axis and sends one multiplier through -1 within one
// step (issue 33: AUTO's pen and tor lost such period doublings, the pair bucketed as a complex
// crossing or, paired the other way, as none). MoebiusPair at mu = -0.01: the pair
// -exp(2 pi (mu +- sqrt(1/4 - omega^2))) meets at omega = 1/2 (modulus exp(-0.02 pi) = 0.94) and
// one passes -1 at omega = sqrt(1/4 - 1e-4) = 0.49989999, 1e-4 later: one PD there, to 1e-8,
// trusted, and no NS.
TEST(Continuation, PeriodDoublingOfAPairMeetingOnTheNegativeAxis) {
  NormalForm system(Kind::MoebiusPair, -0.01, 1, 0.0, 0.7);
  const auto start = circle(system);
  for (const auto& m : start.floquet.multipliers)
    if (!m.trivial) {
      EXPECT_NEAR(std::abs(m.value), std::exp(-0.02 * kPi), 1e-8);  // a pair
    }
  Continuation c(system, 2, options(0.3, 0.7));
  const Branch branch = c.run(start, -1);
  const auto pd = events_of(branch, BifurcationType::PeriodDoubling);
  ASSERT_EQ(pd.size(), 1u) << branch.stop_reason;
  EXPECT_NEAR(pd[0].parameter, std::sqrt(0.25 - 1e-4), 1e-8);
  EXPECT_EQ(pd[0].trust, EventTrust::Trusted) << pd[0].note;
  EXPECT_NEAR(pd[0].crossing.real(), -1.0, 1e-6);
  EXPECT_TRUE(events_of(branch, BifurcationType::NeimarkSacker).empty());
  EXPECT_LT(branch.points.back().parameter, 0.31);  // on to the end of the window
}

// Events near points whose trivial multiplier is off by more than the trust limit are flagged,
// not reported as found: here with a limit no computation can meet.
TEST(Continuation, UntrustedEventsAreFlagged) {
  NormalForm system(Kind::Pitchfork, -0.4);
  const auto start = circle(system);
  auto o = options(-0.5, 0.5);
  o.trust_limit = 1e-16;
  Continuation c(system, 0, o);
  const Branch branch = c.run(start, +1);
  ASSERT_EQ(branch.events.size(), 1u);
  EXPECT_EQ(branch.events[0].trust, EventTrust::TrivialErrorTooLarge);
  EXPECT_NE(branch.events[0].note.find("not trusted"), std::string::npos);
}

// Callbacks see every point as it comes, and a stop request ends the run, keeping the points.
TEST(Continuation, StreamsPointsAndStopsOnRequest) {
  NormalForm system(Kind::Pitchfork, -0.4);
  const auto start = circle(system);
  Continuation c(system, 0, options(-0.5, 0.5));
  int seen = 0;
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint&) { ++seen; };
  callbacks.stop_requested = [&] { return seen >= 4; };
  const Branch branch = c.run(start, +1, callbacks);
  EXPECT_EQ(branch.stop, StopReason::Interrupted) << branch.stop_reason;
  EXPECT_EQ(seen, 4);
  EXPECT_EQ(branch.points.size(), 4u);
  for (std::size_t i = 1; i < branch.points.size(); ++i)
    EXPECT_GT(branch.points[i].parameter, branch.points[i - 1].parameter);
}

}  // namespace
}  // namespace sympathy

namespace sympathy {
namespace {

// What one shooting segment must resolve, recorded in each point: the largest growth of a
// perturbation over a segment, |D^-1 M_k D|_inf. On the Hopf cycle with the transverse state
// w' = (-a + b x) w at a = -1.5, b = 0, w grows by exp(3 T / 2m) over each of m equal segments of
// the period T = 2 pi, exactly, and nothing else grows by more than sqrt(2) (a rotation, the radial
// direction contracting); w's row of M_k has nothing else (w = 0 on the cycle), so the scales
// cancel from it. 1.24e4 on one segment, 111 on two; the monodromy's, exp(3 pi), on both.
TEST(Continuation, PointsRecordTheGrowthOverASegment) {
  const testing::HopfCycle system(true, -1.5, 0.0);
  const PeriodicOrbit start = circle(system);
  for (int m : {1, 2}) {
    ContinuationOptions o = options(-1.6, -1.4);
    o.orbit.shooting.segments = m;
    o.max_points = 2;
    Continuation c(system, system.parameter_index("a"), o);
    const Branch branch = c.run(start, +1);
    ASSERT_EQ(branch.points.size(), 2u) << branch.stop_reason;
    for (const auto& p : branch.points) {
      const double exact = std::exp(-p.parameter * 2 * kPi / m);
      EXPECT_NEAR(p.orbit.segment_growth / exact, 1.0, 1e-6) << m << " segments at " << p.parameter;
      EXPECT_NEAR(p.orbit.monodromy_growth / std::pow(exact, m), 1.0, 1e-6) << m;
      EXPECT_EQ(p.orbit.segments, m);
    }
  }
}

}  // namespace
}  // namespace sympathy
