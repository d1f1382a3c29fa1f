#include "sympathy/continuation/periodic_orbit.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cases/bench/hand_written_systems.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using bench::HandHopf;
using testing::ForcedFloquet;
using testing::HopfCycle;
using testing::TwoHopf;

using testing::kPi;

OrbitOptions tight(int segments = 1) {
  OrbitOptions o;
  o.shooting.segments = segments;
  o.shooting.flow.rtol = 1e-12;
  o.shooting.flow.atol = 1e-14;
  o.newton.residual_tolerance = 1e-11;
  return o;
}

// An orbit only where there is one (issue 32): at the Hopf point itself (mu = 0) Newton followed
// the decaying motion to amplitude 6.7e-4 and reported a converged, stable orbit at the absolute
// noise floor; it must say there is none. A genuine small orbit next to it (mu = 1e-4, radius
// 0.01) still converges to its exact radius, period and multiplier.
TEST(PeriodicOrbit, NoOrbitAtTheHopfPointButTheSmallOneNextToIt) {
  {
    const HandHopf system(Eigen::Vector2d(0.0, 1.0));
    const auto orbit =
        find_periodic_orbit(system, system.default_parameters(), Eigen::Vector2d(0.3, 0.0), {}, {});
    EXPECT_FALSE(orbit.converged()) << orbit.newton.reason;
    EXPECT_EQ(orbit.newton.outcome, NewtonOutcome::Vanishing) << orbit.newton.reason;
    EXPECT_NE(orbit.newton.reason.find("no orbit: the motion decays to the equilibrium"),
              std::string::npos)
        << orbit.newton.reason;
  }
  {
    const double mu = 1e-4, w = 1.0;
    const HandHopf system(Eigen::Vector2d(mu, w));
    const auto orbit = solve_periodic_orbit(system, system.default_parameters(),
                                            Eigen::Vector2d(0.0102, 0.0), 2 * kPi * 1.001, {}, {});
    ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
    // The radius is fixed only to residual / (1 - exp(-4 pi mu)) = 800 x residual so near the
    // Hopf point (the radial multiplier 0.9987): 1e-8 is 1e-6 of it (measured 6e-9).
    EXPECT_NEAR(orbit.state0.norm(), std::sqrt(mu), 1e-8);
    EXPECT_NEAR(orbit.period, 2 * kPi / w, 1e-8);
    for (const auto& m : orbit.floquet.multipliers)
      if (!m.trivial) {
        EXPECT_NEAR(m.value.real(), std::exp(-2 * mu * 2 * kPi / w), 1e-7);
      }
  }
}

// Exact: the unit circle, period 2 pi, multipliers 1 and exp(-4 pi) (radial rate -2), and with
// the transverse state exp(-2 pi a) = exp(-pi), from a guess off the cycle and off the period.
TEST(PeriodicOrbit, HopfCycleToTenDigits) {
  for (bool transverse : {false, true}) {
    HopfCycle system(transverse);
    Eigen::VectorXd guess = Eigen::VectorXd::Zero(system.dimension());
    guess[0] = 1.2;
    guess[1] = 0.1;
    const auto orbit =
        solve_periodic_orbit(system, system.default_parameters(), guess, 6.0, {}, tight());
    ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
    EXPECT_NEAR(orbit.period, 2 * kPi, 1e-10);
    EXPECT_NEAR(orbit.state0.head(2).norm(), 1.0, 1e-10);
    const auto& f = orbit.floquet;
    ASSERT_GE(f.trivial, 0);
    EXPECT_LT(f.trivial_error, 1e-10);
    std::vector<double> expected{std::exp(-4 * kPi)};
    if (transverse) expected.push_back(std::exp(-kPi));
    std::vector<double> others;
    for (const auto& m : f.multipliers)
      if (!m.trivial) {
        EXPECT_NEAR(m.value.imag(), 0.0, 1e-10);
        others.push_back(m.value.real());
      }
    std::sort(expected.begin(), expected.end());
    std::sort(others.begin(), others.end());
    ASSERT_EQ(others.size(), expected.size());
    for (std::size_t k = 0; k < others.size(); ++k) EXPECT_NEAR(others[k], expected[k], 1e-10);
    EXPECT_EQ(f.stability, Stability::Stable);
    EXPECT_EQ(orbit.family_dimension, 0);
    // Newton's diagnostics: iterations, a falling residual, why it stopped.
    EXPECT_GE(orbit.newton.iterations, 2);
    // Below Newton's tolerance: 1e-11, or 20 rtol where that is larger (attainable_tolerance).
    EXPECT_LE(orbit.newton.residual_norms.back(),
              attainable_tolerance(1e-11, 20.0, tight().shooting.flow));
    EXPECT_LT(orbit.newton.residual_norms.back(), orbit.newton.residual_norms.front());
    EXPECT_EQ(orbit.newton.reason, "residual below tolerance");
  }
}

// The same orbit with 1, 3, 5, 10 and 50 segments: the same multipliers, all exact to 1e-10;
// with more than one segment the steps are solved by the sparse LU (UMFPACK).
TEST(PeriodicOrbit, SegmentCountDoesNotChangeMultipliers) {
  HopfCycle system(true);
  Eigen::VectorXd guess(3);
  guess << 1.1, 0.0, 0.05;
  for (int m : {1, 3, 5, 10, 50}) {
    const auto orbit =
        solve_periodic_orbit(system, system.default_parameters(), guess, 6.2, {}, tight(m));
    ASSERT_TRUE(orbit.converged()) << m << ": " << orbit.newton.reason;
    EXPECT_EQ(orbit.newton.sparse, m > 1) << m;
    const auto& mu = orbit.floquet.multipliers;  // by decreasing modulus
    EXPECT_NEAR(mu[0].value.real(), 1.0, 1e-10) << m;
    EXPECT_NEAR(mu[1].value.real(), std::exp(-kPi), 1e-10) << m;
    EXPECT_NEAR(mu[2].value.real(), std::exp(-4 * kPi), 1e-10) << m;
    EXPECT_NEAR(orbit.period, 2 * kPi, 1e-10) << m;
  }
}

// Exponents 0 and -24 exactly (see ForcedFloquet). From 50 segments by periodic Schur the -24
// exponent comes out to 8 digits; from the single product of one shooting segment its
// multiplier, exp(-48 pi) = 2e-66, drowns in the rounding of entries of size 1 and is lost.
TEST(PeriodicOrbit, ForcedFloquetExponentsNeedPeriodicSchur) {
  ForcedFloquet system;
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(2);
  auto exponents = [&](int segments) {
    OrbitOptions o = tight(segments);
    o.shooting.flow.atol = 1e-20;  // relative accuracy for the fast-decaying column
    const auto orbit =
        solve_periodic_orbit(system, system.default_parameters(), zero, 2 * kPi, {}, o);
    EXPECT_TRUE(orbit.converged());
    EXPECT_EQ(orbit.floquet.trivial, -1);  // forced: no trivial multiplier
    std::vector<double> e;
    for (const auto& m : orbit.floquet.multipliers) e.push_back(m.log_modulus / (2 * kPi));
    return e;  // decreasing
  };
  const auto periodic = exponents(50);
  EXPECT_NEAR(periodic[0], 0.0, 1e-9);
  EXPECT_NEAR(periodic[1], -24.0, 24.0 * 1e-8);
  const auto single = exponents(1);
  EXPECT_NEAR(single[0], 0.0, 1e-9);
  EXPECT_GT(std::abs(single[1] + 24.0), 10.0);  // lost: about -6, the rounding level
}

// A continuum of orbits (two uncoupled oscillators, free phase between them): Newton still
// converges, with minimum-norm steps, and reports a one-parameter family whose second
// multiplier at 1 is structural; the remaining multipliers are exp(-4 pi) twice.
TEST(PeriodicOrbit, FamilyOfOrbits) {
  TwoHopf system;
  Eigen::VectorXd guess(4);
  guess << 1.1, 0.0, 0.3, 0.9;
  for (int m : {1, 4}) {
    const auto orbit =
        solve_periodic_orbit(system, system.default_parameters(), guess, 6.0, {}, tight(m));
    ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
    EXPECT_EQ(orbit.family_dimension, 1);
    EXPECT_EQ(orbit.floquet.structural, 1);
    EXPECT_LT(orbit.floquet.trivial_error, 1e-10);
    EXPECT_NEAR(orbit.period, 2 * kPi, 1e-10);
    int at_one = 0;
    for (const auto& mu : orbit.floquet.multipliers) {
      if (std::abs(mu.value - 1.0) < 1e-10) {
        ++at_one;
        EXPECT_TRUE(mu.trivial || mu.structural);
      } else {
        EXPECT_NEAR(mu.value.real(), std::exp(-4 * kPi), 1e-10);
      }
    }
    EXPECT_EQ(at_one, 2);
    EXPECT_EQ(orbit.floquet.stability, Stability::Stable);
  }
}

// Kept in the subspace {x2 = -x1, y2 = -y1}, Newton finds the antiphase member of the family.
TEST(PeriodicOrbit, StaysInInvariantSubspace) {
  TwoHopf system;
  const InvariantSubspace antiphase(4, {{2, 0, -1.0}, {3, 1, -1.0}});
  EXPECT_LT(
      antiphase.invariance_defect(system, system.default_parameters(), Eigen::VectorXd::Ones(4)),
      1e-15);
  Eigen::VectorXd guess(4);
  guess << 1.1, 0.2, -0.7, 0.1;
  const auto orbit =
      solve_periodic_orbit(system, system.default_parameters(), guess, 6.0, antiphase, tight());
  ASSERT_TRUE(orbit.converged());
  EXPECT_EQ(orbit.state0[2], -orbit.state0[0]);
  EXPECT_EQ(orbit.state0[3], -orbit.state0[1]);
}

// From a start: the transient and the first return give the period; then Newton.
TEST(PeriodicOrbit, FoundFromAStart) {
  HopfCycle system(true);
  Eigen::VectorXd start(3);
  start << 0.3, 0.0, 1.0;
  OrbitOptions o = tight();
  o.transient = 10.0;
  const auto orbit = find_periodic_orbit(system, system.default_parameters(), start, {}, o);
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_NEAR(orbit.period, 2 * kPi, 1e-10);
  EXPECT_LE(orbit.newton.iterations, 4);
}

// A slowly approached cycle: the pitchfork form at mu = -0.1, the unit circle of period 2 pi with
// multipliers exp(-4 pi) (radial) and exp(2 pi mu) = exp(-0.2 pi) = 0.53 (w), from w = 0.1. The
// motion in one period falls to 1e-4 of the state only after about 70 s (w about 2e-4), so the
// 60 s transient never settles; at the check at 40.5 s (w about 2e-3) it moves by 8e-4, and
// Newton tried there (OrbitOptions::early_newton_below) finds the same orbit, exactly.
TEST(PeriodicOrbit, EarlyNewtonFindsTheOrbitTheTransientApproaches) {
  using testing::NormalForm;
  const NormalForm system(NormalForm::Kind::Pitchfork, -0.1);
  Eigen::VectorXd start(3);
  start << 1.0, 0.0, 0.1;
  OrbitOptions whole = tight();
  whole.early_newton_below = 0.0;  // the whole 60 s
  OrbitOptions early = tight();
  const auto p = system.default_parameters();
  const auto a = find_periodic_orbit(system, p, start, {}, whole);
  const auto b = find_periodic_orbit(system, p, start, {}, early);
  for (const auto* orbit : {&a, &b}) {
    ASSERT_TRUE(orbit->converged()) << orbit->newton.reason;
    EXPECT_NEAR(orbit->period, 2 * kPi, 1e-10);
    EXPECT_NEAR(orbit->state0.head(2).norm(), 1.0, 1e-10);
    EXPECT_NEAR(orbit->state0[2], 0.0, 1e-10);
    std::vector<double> others;
    for (const auto& m : orbit->floquet.multipliers)
      if (!m.trivial) others.push_back(m.value.real());
    ASSERT_EQ(others.size(), 2u);
    std::sort(others.begin(), others.end());
    EXPECT_NEAR(others[0], std::exp(-4 * kPi), 1e-10);
    EXPECT_NEAR(others[1], std::exp(-0.2 * kPi), 1e-9);
    EXPECT_LT(orbit->floquet.trivial_error, 1e-9);
  }
  // The early path was taken: the transient stopped at a check (its one-second integrations are
  // most of the calls: 74 with the whole transient, 55 here). On this smooth system a transient
  // second costs little against Newton's runs at rtol 1e-12, so steps are no measure of it here.
  EXPECT_LT(b.flow.calls + 10, a.flow.calls) << a.flow.calls << " " << b.flow.calls;
}

// Newton tried early takes only an orbit the transient could be approaching: one stable where the
// transient runs. The pitchfork form at mu = +0.1 from w = 1e-3 on the circle: the circle (w = 0)
// is unstable in w (multiplier exp(0.2 pi)), and the transient leaves it for the cycles at
// w = +-sqrt(0.1); the orbit found is the one at w = +sqrt(0.1), whatever the checks met.
TEST(PeriodicOrbit, EarlyNewtonTakesNoUnstableOrbit) {
  using testing::NormalForm;
  const NormalForm system(NormalForm::Kind::Pitchfork, 0.1);
  Eigen::VectorXd start(3);
  start << 1.0, 0.0, 1e-3;
  const auto orbit = find_periodic_orbit(system, system.default_parameters(), start, {}, tight());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_NEAR(orbit.state0[2], std::sqrt(0.1), 1e-9);
  EXPECT_EQ(orbit.floquet.stability, Stability::Stable);
}

// An equilibrium has no return to the section: a clear failure, not a crash.
TEST(PeriodicOrbit, NoOrbitIsReported) {
  testing::Decay system(1.0);
  Eigen::VectorXd start(1);
  start << 1.0;
  OrbitOptions o;
  o.transient = 1.0;
  o.max_period = 2.0;
  const auto orbit = find_periodic_orbit(system, system.default_parameters(), start, {}, o);
  EXPECT_FALSE(orbit.converged());
  EXPECT_NE(orbit.newton.reason.find("no return to the section"), std::string::npos);
}

}  // namespace
}  // namespace sympathy
