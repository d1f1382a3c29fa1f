// Periodic orbits of piecewise-smooth systems by shooting: the monodromy carried across every
// crossing by its saltation matrix (core/saltation.hpp), so Newton converges quadratically and the
// Floquet multipliers are the hybrid flow's. Against the closed forms of
// tests/support/test_systems.hpp (Relay, ImpactOscillator); a branch of them ends where an orbit
// grazes a surface (grazing.hpp), located where the closed form has it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/branch_switching.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
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

// A smooth planar field (Derived::evaluate, states x and y) with a switching surface x = p[C]
// across which nothing jumps: the regions share the field, and the surface only counts crossings
// (where their number changes, an orbit grazes it).
template <class Derived, int C>
class MarkedAtX : public AutoDiffHybridSystem<Derived> {
 public:
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate_on_sides(double t, const T* z, const P* p, T* dz, const int*) const {
    static_cast<const Derived&>(*this).evaluate(t, z, p, dz);
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double* p, double* g) const override {
    g[0] = z[0] - p[C];
  }
  double switching_gradient(double, const double*, const double*, int, double* h_z) const override {
    h_z[0] = 1.0;
    h_z[1] = 0.0;
    return 0.0;
  }
  std::string switching_name(int) const override { return "x = c"; }
  double switching_parameter_derivative(double, const double*, const double*, int,
                                        int parameter) const override {
    return parameter == C ? -1.0 : 0.0;
  }
};

// The Hopf normal form x' = mu x - y - x r^2, y' = x + mu y - y r^2 (circles of radius sqrt(mu),
// period 2 pi) with a switching surface x = c across which nothing jumps: its orbits cross it
// twice a period where sqrt(mu) > c, never where sqrt(mu) < c, and graze it at mu = c^2 exactly.
class HopfWithMark final : public MarkedAtX<HopfWithMark, 1> {
 public:
  explicit HopfWithMark(double mu, double c) {
    set_parameter_layout({{"mu", {0}}, {"c", {1}}}, {mu, c});
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    dz[0] = p[0] * z[0] - z[1] - z[0] * r2;
    dz[1] = z[0] + p[0] * z[1] - z[1] * r2;
  }
};

// A circle of radius 1 + 1e-8 passes x = 1 for 2.8e-4 of its period of 2 pi, within one step of
// the integrator at rtol 1e-11 (about 400 steps a period, 0.016): both crossings are counted (and
// none on a circle of radius 1 - 1e-8), where the root finding alone, comparing signs at the
// steps' ends, saw none (measured; at 1 + 1e-6 a step's end happened to fall inside). At 1 +
// 1e-10, the integration's own accuracy, neither sees them.
TEST(HybridOrbit, TwoCrossingsWithinOneStepAreCounted) {
  FlowOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  for (const double radius : {1.0 + 1e-8, 1.0 - 1e-8}) {
    const HopfWithMark system(radius * radius, 1.0);
    Flow flow(system, o);
    const Eigen::VectorXd end = flow.advance(
        Eigen::Vector2d(0.0, radius), system.default_parameters(), 0.0, 2 * std::numbers::pi);
    EXPECT_NEAR(end[1], radius, 1e-9);
    EXPECT_EQ(flow.crossings(), std::vector<int>{radius > 1.0 ? 2 : 0}) << radius;
  }
}

// From mu = 2.25 (radius 1.5) down towards 0.25: the branch ends at the grazing, mu = c^2 = 1,
// its stop named; from mu = 0.25 up, the same point from the other side. Each direction about 30
// bisection probes, to the location tolerance (1e-8 relative; measured: 2e-9 and 1e-9 off). The
// orbits just past the grazing cross x = 1 twice within one integration step: before the flow
// looked for such excursions (Flow::hidden_excursion) the count missed them, and the grazing was
// located at mu = 1.00038.
TEST(HybridOrbit, BranchEndsWhereItsOrbitGrazesASurface) {
  const double c = 1.0;
  for (const double from : {2.25, 0.25}) {
    const HopfWithMark system(from, c);
    const auto start = solve_periodic_orbit(system, system.default_parameters(),
                                            Eigen::Vector2d(0.0, std::sqrt(from)),
                                            2 * std::numbers::pi, {}, hybrid_orbit_options());
    ASSERT_TRUE(start.converged()) << start.newton.reason;
    ContinuationOptions o;
    o.lower = 0.2;
    o.upper = 2.3;
    o.orbit.shooting.flow.rtol = 1e-11;
    o.orbit.shooting.flow.atol = 1e-13;
    Continuation continuation(system, system.parameter_index("mu"), o);
    const Branch branch = continuation.run(start, from > 1.0 ? -1 : +1);
    ASSERT_EQ(branch.stop, StopReason::Nonsmooth) << from << ": " << branch.stop_reason;
    EXPECT_NE(branch.stop_reason.find("grazing near mu = "), std::string::npos)
        << branch.stop_reason;
    EXPECT_NE(branch.stop_reason.find(from > 1.0 ? "x = c crossed 2 -> 0 times"
                                                 : "x = c crossed 0 -> 2 times"),
              std::string::npos)
        << branch.stop_reason;
    // The last point lies before the grazing: every point on the starting side.
    for (const auto& p : branch.points)
      EXPECT_EQ(p.parameter > c * c, from > 1.0) << from << " at " << p.parameter;
    const double located =
        std::stod(branch.stop_reason.substr(branch.stop_reason.find("mu = ") + 5));
    EXPECT_NEAR(located, c * c, 1e-8) << branch.stop_reason;
  }
}

// The fold normal form's cycles (r^2 solving mu + (1 + a) r^2 - r^4 = 0, period 2 pi) with a
// surface x = c across which nothing jumps: its LP curve mu = -(1 + a)^2 / 4, at r^2 = (1 + a) /
// 2, grazes the surface where r = c, at a = 2 c^2 - 1 exactly. Parameters mu, a, c.
class FoldWithMark final : public MarkedAtX<FoldWithMark, 2> {
 public:
  FoldWithMark(double mu, double a, double c) {
    set_parameter_layout({{"mu", {0}}, {"a", {1}}, {"c", {2}}}, {mu, a, c});
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    const T g = p[0] + (1.0 + p[1]) * r2 - r2 * r2;
    dz[0] = -z[1] + z[0] * g;
    dz[1] = z[0] + z[1] * g;
  }
};

// The LP curve from the fold at a = 0 (mu = -1/4, r^2 = 1/2), in a over [-0.5, 0.5]: upward to
// the window's edge, downward to the grazing at a = 2 c^2 - 1 = -0.28 (c = 0.6), where it ends,
// its stop named and located by bisection (measured: 2.8e-10 off); every point on the parabola and
// on the crossing side.
TEST(HybridOrbit, CurveEndsWhereItsOrbitGrazesASurface) {
  const double c = 0.6;
  const FoldWithMark system(-0.2, 0.0, c);
  const double r2 = 0.5 * (1.0 + std::sqrt(0.2));  // the outer cycle at mu = -0.2
  OrbitOptions orbit = hybrid_orbit_options();
  orbit.shooting.flow.rtol = 1e-11;
  orbit.shooting.flow.atol = 1e-13;
  const auto start =
      solve_periodic_orbit(system, system.default_parameters(), Eigen::Vector2d(std::sqrt(r2), 0.0),
                           2 * std::numbers::pi, {}, orbit);
  ASSERT_TRUE(start.converged()) << start.newton.reason;
  ContinuationOptions o;
  o.lower = -0.5;
  o.upper = 0.5;
  o.orbit = orbit;
  Continuation continuation(system, 0, o);
  const Branch branch = continuation.run(start, -1);
  const auto fold = std::ranges::find_if(
      branch.events, [](const Bifurcation& e) { return e.type == BifurcationType::Fold; });
  ASSERT_NE(fold, branch.events.end()) << branch.stop_reason;
  EXPECT_NEAR(fold->parameter, -0.25, 1e-8);
  CurveOptions w;
  w.first_lower = -1.0;
  w.first_upper = 0.0;
  w.second_lower = -0.5;
  w.second_upper = 0.5;
  w.orbit = orbit;
  const BifurcationCurve curve = continue_curve(system, branch, *fold, 1, w);
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  EXPECT_NE(curve.stop_reason.find("grazing near mu = "), std::string::npos) << curve.stop_reason;
  EXPECT_NE(curve.stop_reason.find("x = c crossed 2 -> 0 times"), std::string::npos)
      << curve.stop_reason;
  const double a_grazing = 2 * c * c - 1.0;
  for (const auto& p : curve.points) {
    EXPECT_GT(p.second, a_grazing);
    EXPECT_NEAR(p.first, -(1.0 + p.second) * (1.0 + p.second) / 4.0, 1e-8) << p.second;
  }
  const auto at = curve.stop_reason.find(", a = ");
  ASSERT_NE(at, std::string::npos) << curve.stop_reason;
  EXPECT_NEAR(std::stod(curve.stop_reason.substr(at + 6)), a_grazing, 1e-8) << curve.stop_reason;
}

// The relay (x, v, with sign(v)) beside a transverse pitchfork w' = mu w - w^3: the relay's orbit
// with w = 0 has the multipliers 1, rho^2 and exp(mu T), a branch point at mu = 0, and the
// branches born there, w = +-sqrt(mu), carry the same relay orbit (period 2 pi / w_r). Its
// crossings jump v' by 2a, so the monodromy has a nontrivial saltation factor. Parameters mu,
// zeta, a.
class RelayWithPitchfork final : public AutoDiffHybridSystem<RelayWithPitchfork> {
 public:
  explicit RelayWithPitchfork(double mu) {
    set_parameter_layout({{"mu", {0}}, {"zeta", {1}}, {"a", {2}}}, {mu, 0.1, 0.5});
  }
  int dimension() const override { return 3; }
  std::vector<std::string> state_names() const override { return {"x", "v", "w"}; }
  template <class T, class P>
  void evaluate(double t, const T* z, const P* p, T* dz) const {
    const int side = value_of(z[1]) >= 0.0 ? 1 : -1;
    evaluate_on_sides(t, z, p, dz, &side);
  }
  template <class T, class P>
  void evaluate_on_sides(double, const T* z, const P* p, T* dz, const int* sides) const {
    dz[0] = z[1];
    dz[1] = -z[0] - 2.0 * p[1] * z[1] + p[2] * static_cast<double>(sides[0]);
    dz[2] = p[0] * z[2] - z[2] * z[2] * z[2];
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    g[0] = z[1];
  }
  double switching_gradient(double, const double*, const double*, int, double* h_z) const override {
    h_z[0] = 0.0;
    h_z[1] = 1.0;
    h_z[2] = 0.0;
    return 0.0;
  }
};

// From the relay orbit at mu = -0.3 up: the BP at mu = 0 (to 1e-8), and the branch switched
// there has w^2 = mu and the relay's period on every point beyond it (1e-8, the orbits' accuracy
// at rtol 1e-12), both halves.
TEST(HybridOrbit, BranchSwitchedAtAPitchforkOfHybridOrbits) {
  const RelayWithPitchfork system(-0.3);
  const double zeta = 0.1, a = 0.5;
  const Eigen::Vector2d quarter = Relay::quarter_point(zeta, a);
  const double period = 2 * std::numbers::pi / Relay::angular_frequency(zeta);
  const auto start = solve_periodic_orbit(system, system.default_parameters(),
                                          Eigen::Vector3d(quarter[0], quarter[1], 0.0), period, {},
                                          hybrid_orbit_options());
  ASSERT_TRUE(start.converged()) << start.newton.reason;
  ContinuationOptions o;
  o.lower = -0.3;
  o.upper = 0.3;
  o.orbit = hybrid_orbit_options();
  Continuation continuation(system, 0, o);
  const Branch old = continuation.run(start, +1);
  const auto bp = std::ranges::find_if(
      old.events, [](const Bifurcation& e) { return e.type == BifurcationType::BranchPoint; });
  ASSERT_NE(bp, old.events.end()) << old.stop_reason;
  EXPECT_NEAR(bp->parameter, 0.0, 1e-8);
  const Branch born = switch_branch(system, old, *bp, o);
  int positive = 0, negative = 0;
  for (const auto& p : born.points) {
    const Eigen::VectorXd& z = p.orbit.state0;
    EXPECT_NEAR(z[2] * z[2], p.parameter, 1e-8) << "mu = " << p.parameter;
    EXPECT_NEAR(p.orbit.period, period, 1e-8);
    if (p.parameter > 1e-3) (z[2] > 0 ? positive : negative) += 1;
  }
  EXPECT_GT(positive, 0) << born.stop_reason;
  EXPECT_GT(negative, 0) << born.stop_reason;
}

}  // namespace
}  // namespace sympathy
