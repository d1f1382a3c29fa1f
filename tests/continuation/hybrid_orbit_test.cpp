// Periodic orbits of piecewise-smooth systems by shooting: the monodromy carried across every
// crossing by its saltation matrix (core/saltation.hpp), so Newton converges quadratically and the
// Floquet multipliers are the hybrid flow's. Against the closed forms of
// tests/support/test_systems.hpp (Relay, ImpactOscillator).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/continuation/periodic_orbit.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::ImpactOscillator;
using testing::Relay;

// Shooting at rtol 1e-12 (the multipliers' noise floor is about rtol times the monodromy's
// growth, here of order one), Newton to 1e-11.
OrbitOptions hybrid_orbit_options() {
  OrbitOptions o;
  o.shooting.flow.rtol = 1e-12;
  o.shooting.flow.atol = 1e-14;
  o.newton.residual_tolerance = 1e-11;
  return o;
}

// The multipliers other than the trivial and structural ones, by decreasing modulus.
std::vector<std::complex<double>> hybrid_nontrivial(const PeriodicOrbit& orbit) {
  std::vector<std::complex<double>> values;
  for (const auto& mu : orbit.floquet.multipliers)
    if (!mu.trivial && !mu.structural) values.push_back(mu.value);
  return values;
}

// The relay's symmetric orbit: period 2 pi / w and multipliers 1, rho^2 exactly (Relay). From a
// guess 2% off in the state and 1% in the period, on one and on three shooting segments.
// Measured: the period within 7e-12, the multipliers within 1e-11, in three Newton iterations (the
// quadratic convergence of an exact Jacobian: the monodromy with its saltation matrices).
TEST(HybridOrbit, RelayPeriodAndMultipliersAreExact) {
  const double zeta = 0.1, a = 0.5;
  const Relay system(zeta, a);
  const double period = 2 * std::numbers::pi / Relay::angular_frequency(zeta);
  const double rho = Relay::contraction(zeta);
  const Eigen::Vector2d guess = Relay::quarter_point(zeta, a) + Eigen::Vector2d(0.02, -0.02);
  for (int segments : {1, 3}) {
    OrbitOptions o = hybrid_orbit_options();
    o.shooting.segments = segments;
    const auto orbit =
        solve_periodic_orbit(system, system.default_parameters(), guess, 1.01 * period, {}, o);
    ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
    EXPECT_LE(orbit.newton.iterations, 5);
    EXPECT_NEAR(orbit.period, period, 1e-9);
    EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
    const auto others = hybrid_nontrivial(orbit);
    ASSERT_EQ(others.size(), 1u);
    EXPECT_NEAR(others[0].real(), rho * rho, 1e-8);
    EXPECT_EQ(others[0].imag(), 0.0);
    EXPECT_EQ(orbit.floquet.stability, Stability::Stable);
    // On the exact orbit: the amplitude A is reached where v changes sign, and |x| <= A.
    EXPECT_LE(std::abs(orbit.state0[0]), Relay::amplitude(zeta, a) + 1e-9);
  }
}

// The impact oscillator's period-one orbit: period pi / w, multipliers 1 and e rho
// (ImpactOscillator), the reset and its saltation (R_z = diag(1, -e)) in the monodromy.
// Measured: the period within 8.5e-12, the multipliers within 5e-12, three Newton iterations.
TEST(HybridOrbit, ImpactOscillatorPeriodOneOrbitIsExact) {
  const double zeta = 0.1, e = 0.8, kick = 1.0;
  const ImpactOscillator system(zeta, e, kick);
  const double period = ImpactOscillator::period(zeta);
  const double w = std::sqrt(1.0 - zeta * zeta);
  // Half way through the arc from the wall (w t = pi / 2): x = V e^(-zeta t) / w,
  // v = -V e^(-zeta t) zeta / w; the guess 3% off.
  const double arc = ImpactOscillator::impact_velocity(zeta, e, kick) *
                     std::exp(-zeta * std::numbers::pi / (2 * w)) / w;
  const Eigen::Vector2d guess(1.03 * arc, -0.97 * arc * zeta);
  const auto orbit = solve_periodic_orbit(system, system.default_parameters(), guess, 0.98 * period,
                                          {}, hybrid_orbit_options());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_NEAR(orbit.period, period, 1e-9);
  EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
  const auto others = hybrid_nontrivial(orbit);
  ASSERT_EQ(others.size(), 1u);
  EXPECT_NEAR(others[0].real(), e * ImpactOscillator::contraction(zeta), 1e-8);
  EXPECT_EQ(orbit.floquet.stability, Stability::Stable);
}

// Two uncoupled relays in phase: every crossing is two simultaneous ones whose saltation matrices
// commute (each acts on its own relay's velocity). The orbit belongs to a family (the relative
// phase is free): multipliers 1 (trivial), 1 (structural), rho^2 twice. Measured: the period
// within 1.2e-11, the multipliers within 6e-12.
TEST(HybridOrbit, TwoRelaysInPhaseCrossTogether) {
  const double zeta = 0.1, a = 0.5;
  const Relay system(zeta, a, 2);
  const double period = 2 * std::numbers::pi / Relay::angular_frequency(zeta);
  const double rho = Relay::contraction(zeta);
  const Eigen::Vector2d q = Relay::quarter_point(zeta, a);
  const Eigen::Vector4d guess(q[0] + 0.01, q[1], q[0] + 0.01, q[1]);
  const auto orbit = solve_periodic_orbit(system, system.default_parameters(), guess, 1.01 * period,
                                          {}, hybrid_orbit_options());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_NEAR(orbit.period, period, 1e-9);
  EXPECT_EQ(orbit.family_dimension, 1);
  EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
  const auto others = hybrid_nontrivial(orbit);
  ASSERT_EQ(others.size(), 2u);
  for (const auto& mu : others) EXPECT_NEAR(mu.real(), rho * rho, 1e-8);
}

}  // namespace
}  // namespace sympathy
