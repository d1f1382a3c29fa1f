// Flows of piecewise-smooth systems (HybridSystem): crossings located and restarted, the state
// sensitivities carried across by the saltation matrix, the parameter sensitivities by its
// parameter jump, resets applied, simultaneous crossings merged and their order checked. Against
// the closed forms of tests/support/test_systems.hpp (Relay, ImpactOscillator) and central
// differences of the flow map.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/core/flow.hpp"
#include "sympathy/core/saltation.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::ImpactOscillator;
using testing::Relay;

// The three integrators the flow offers, at rtol 1e-12.
std::vector<FlowOptions> hybrid_flow_settings() {
  std::vector<FlowOptions> settings;
  FlowOptions bdf;
  bdf.rtol = 1e-12;
  bdf.atol = 1e-14;
  settings.push_back(bdf);
  FlowOptions adams = bdf;
  adams.method = Method::Adams;
  adams.nonlinear_solver = NonlinearSolver::FixedPoint;
  adams.sensitivities = Sensitivities::Augmented;
  settings.push_back(adams);
  FlowOptions erk = bdf;
  erk.method = Method::ERK;
  erk.sensitivities = Sensitivities::Augmented;
  settings.push_back(erk);
  return settings;
}

// e^(M t) for x'' + 2 zeta x' + x = const (M = [0 1; -1 -2 zeta]), w = sqrt(1 - zeta^2).
Eigen::Matrix2d hybrid_damped_transition(double zeta, double t) {
  const double w = std::sqrt(1.0 - zeta * zeta);
  const double c = std::cos(w * t), s = std::sin(w * t), e = std::exp(-zeta * t);
  return e * Eigen::Matrix2d{{c + zeta / w * s, s / w}, {-s / w, c - zeta / w * s}};
}

// Central differences of the flow map z0 -> z(t1) (or p -> z(t1) for a parameter), extrapolated
// (Richardson: (4 D(h) - D(2 h)) / 3, truncation O(h^4)). The flow at rtol 1e-12 is a function of
// z0 with an error of about 1e-11 that is not smooth in z0: plain central differences at h = 1e-4
// were off by 6e-7 in truncation (zeta's column) and 4e-7 in rounding (their error at h = 1e-3 was
// 6e-5, at 3e-5 still 4e-7); extrapolated at h = 1e-3 the truncation is below the rounding,
// about 1.5 * 1e-11 / h ~ 2e-8.
constexpr double kHybridDifferenceStep = 1e-3;

// Measured: the extrapolated differences agree with the sensitivities to 2.9e-8 at worst (relay
// and impact, every integrator); held to 1e-7. A saltation matrix left out is off at order one
// (the relay's v-v entry by the factor (A + a) / (A - a) = 5.4).
constexpr double kHybridDifferenceTolerance = 1e-7;

template <class Map>
Eigen::MatrixXd hybrid_extrapolated_difference(const Map& map, double h) {
  const auto central = [&](double step) { return ((map(step) - map(-step)) / (2 * step)).eval(); };
  return (4 * central(h) - central(2 * h)) / 3;
}

Eigen::MatrixXd hybrid_transition_by_differences(Flow& flow, const Eigen::VectorXd& z0,
                                                 const ParameterValues& p, double t1) {
  const int n = static_cast<int>(z0.size());
  Eigen::MatrixXd m(n, n);
  for (int j = 0; j < n; ++j)
    m.col(j) = hybrid_extrapolated_difference(
        [&](double step) {
          Eigen::VectorXd z = z0;
          z[j] += step;
          return flow.advance(z, p, 0.0, t1);
        },
        kHybridDifferenceStep);
  return m;
}

Eigen::VectorXd hybrid_parameter_by_differences(Flow& flow, const OdeSystem& system,
                                                const Eigen::VectorXd& z0, const ParameterValues& p,
                                                int parameter, double t1) {
  const double value = system.parameter(p, parameter);
  return hybrid_extrapolated_difference(
      [&](double step) {
        return flow.advance(z0, system.with_parameter(p, parameter, value + step), 0.0, t1);
      },
      kHybridDifferenceStep);
}

// From a quarter swing after the bottom turning point the relay reaches its top turning point
// (x = A, v = 0) after exactly pi / (2 w); 0.7 later the transition is exactly
// e^(M 0.7) S e^(M pi / (2 w)), S = diag(1, (A + a) / (A - a)) (test_systems.hpp). Measured
// agreement: below 1e-10 with each integrator at rtol 1e-12.
// The transition and the sensitivity columns of `parameters` from z0 over [0, t1], with each of
// hybrid_flow_settings, against central differences of the flow map (kHybridDifferenceTolerance),
// the crossings counted.
void expect_sensitivities_match_differences(const OdeSystem& system, const Eigen::VectorXd& z0,
                                            double t1, const std::vector<int>& parameters,
                                            long switchings) {
  const auto p = system.default_parameters();
  for (const FlowOptions& o : hybrid_flow_settings()) {
    Flow flow(system, o);
    const auto r = flow.advance_with_sensitivities(z0, p, 0.0, t1, true, parameters);
    EXPECT_EQ(flow.statistics().switchings, switchings);
    const Eigen::MatrixXd differences = hybrid_transition_by_differences(flow, z0, p, t1);
    EXPECT_LT((r.transition - differences).cwiseAbs().maxCoeff(), kHybridDifferenceTolerance)
        << to_string(o.method);
    for (int k : parameters) {
      const Eigen::VectorXd column = hybrid_parameter_by_differences(flow, system, z0, p, k, t1);
      EXPECT_LT((r.parameter_sensitivities.col(k) - column).cwiseAbs().maxCoeff(),
                kHybridDifferenceTolerance)
          << to_string(o.method) << " parameter " << k;
    }
  }
}

TEST(HybridFlow, RelayTransitionAcrossATurningPointIsExact) {
  const double zeta = 0.1, a = 0.5;
  const Relay system(zeta, a);
  const auto p = system.default_parameters();
  const double w = Relay::angular_frequency(zeta), amplitude = Relay::amplitude(zeta, a);
  const double tau = std::numbers::pi / (2 * w), after = 0.7;
  const Eigen::Matrix2d saltation{{1.0, 0.0}, {0.0, (amplitude + a) / (amplitude - a)}};
  const Eigen::Matrix2d exact =
      hybrid_damped_transition(zeta, after) * saltation * hybrid_damped_transition(zeta, tau);
  const Eigen::VectorXd z0 = Relay::quarter_point(zeta, a);
  for (const FlowOptions& o : hybrid_flow_settings()) {
    Flow flow(system, o);
    const auto r = flow.advance_with_sensitivities(z0, p, 0.0, tau + after);
    EXPECT_EQ(flow.statistics().switchings, 1);
    EXPECT_LT((r.transition - exact).cwiseAbs().maxCoeff(), 1e-10) << to_string(o.method);
    // Without the saltation the v-v entry would be off by the factor (A + a) / (A - a) = 5.4.
  }
}

// The saltation matrix against central differences of the flow map across the crossing, and
// the parameter columns (a moves the field, zeta the flow; neither moves the surface v = 0) too.
// Measured: within 2.9e-8 (kHybridDifferenceTolerance).
TEST(HybridFlow, RelaySensitivitiesMatchCentralDifferences) {
  const Relay system(0.1, 0.5);
  const Eigen::VectorXd z0 = Relay::quarter_point(0.1, 0.5);
  const double t1 = 5.5;  // crosses the top (t = 1.58) and the bottom (4.74) turning points
  expect_sensitivities_match_differences(system, z0, t1, {0, 1}, 2);
}

// Without the saltation matrix the sensitivities would be those of a smooth flow: the check
// above fails then. Held here on the formula: the saltation matrix of the relay's top turning
// point has the closed-form entry (A + a) / (A - a).
TEST(HybridFlow, SaltationMatrixOfTheRelayTurningPoint) {
  const double a = 0.5, amplitude = Relay::amplitude(0.1, a);
  const Eigen::Vector2d f_minus(0.0, a - amplitude), f_plus(0.0, -a - amplitude);
  const Eigen::RowVector2d h_z(0.0, 1.0);
  const Eigen::MatrixXd s =
      saltation_matrix(f_minus, f_plus, h_z, 0.0, Eigen::Matrix2d::Identity());
  EXPECT_DOUBLE_EQ(s(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(s(0, 1), 0.0);
  EXPECT_DOUBLE_EQ(s(1, 0), 0.0);
  EXPECT_NEAR(s(1, 1), (amplitude + a) / (amplitude - a), 1e-15 * s(1, 1));
}

// The impact oscillator: the reset v+ = kick - e v- at the wall, and its saltation with
// R_z = diag(1, -e) and R_p; from the top of the arc one impact later, against central
// differences (state and the parameters e and kick, which enter through R_p only).
TEST(HybridFlow, ImpactSensitivitiesMatchCentralDifferences) {
  const double zeta = 0.1, e = 0.8, kick = 1.0;
  const ImpactOscillator system(zeta, e, kick);
  const auto p = system.default_parameters();
  const Eigen::Vector2d z0(0.9, -0.2);  // above the wall, falling
  const double t1 = 2.5;                // the wall at about t = 1.47, then the rise
  expect_sensitivities_match_differences(system, z0, t1, {0, 1, 2}, 1);
  // Reflected, not through the wall.
  EXPECT_GT(Flow(system, hybrid_flow_settings().front()).advance(z0, p, 0.0, t1)[0], 0.0);
}

// Two uncoupled relays from equal starts cross their surfaces at the same instants: one event
// each time (two a period, not four), and saltation matrices that commute, so the transition is
// the single relay's in each block, exactly (block diagonal, the off-diagonal blocks zero).
TEST(HybridFlow, SimultaneousCommutingCrossingsAreOneEvent) {
  const double zeta = 0.1, a = 0.5;
  const Relay one(zeta, a), two(zeta, a, 2);
  const Eigen::Vector2d q = Relay::quarter_point(zeta, a);
  const Eigen::Vector4d z0(q[0], q[1], q[0], q[1]);
  const double period = 2 * std::numbers::pi / Relay::angular_frequency(zeta);
  for (const FlowOptions& o : hybrid_flow_settings()) {
    Flow single(one, o), pair(two, o);
    const auto r1 = single.advance_with_sensitivities(q, one.default_parameters(), 0.0, period);
    const auto r2 = pair.advance_with_sensitivities(z0, two.default_parameters(), 0.0, period);
    EXPECT_EQ(pair.statistics().switchings, 2) << to_string(o.method);
    EXPECT_LT((r2.transition.topLeftCorner(2, 2) - r1.transition).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_LT((r2.transition.bottomRightCorner(2, 2) - r1.transition).cwiseAbs().maxCoeff(), 1e-10);
    EXPECT_EQ(r2.transition.topRightCorner(2, 2).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_EQ(r2.transition.bottomLeftCorner(2, 2).cwiseAbs().maxCoeff(), 0.0);
  }
}

// Coupled relays (c = 0.3: a turning point of one jumps the other's acceleration) crossing at one
// instant: the saltation matrices do not commute, the flow map has a corner, and the flow says so
// instead of returning either one-sided derivative. A plain integration goes through.
TEST(HybridFlow, SimultaneousNonCommutingCrossingsAreACorner) {
  const Relay two(0.1, 0.5, 2, 0.3);
  const Eigen::Vector2d q = Relay::quarter_point(0.1, 0.5);
  const Eigen::Vector4d z0(q[0], q[1], q[0], q[1]);
  for (const FlowOptions& o : hybrid_flow_settings()) {
    Flow flow(two, o);
    EXPECT_NO_THROW(flow.advance(z0, two.default_parameters(), 0.0, 4.0));
    try {
      flow.advance_with_sensitivities(z0, two.default_parameters(), 0.0, 4.0);
      ADD_FAILURE() << "no corner reported with " << to_string(o.method);
    } catch (const NonsmoothFlowError& e) {
      EXPECT_NE(std::string(e.what()).find("do not commute"), std::string::npos) << e.what();
    }
  }
}

// A crossing where the flow only touches the surface (h_z f- + h_t = 0) has no saltation matrix:
// the relay at its centre x = a with v = 0, where v' = -x - 2 zeta v + a = 0 on the side v > 0.
// Reported, not divided by zero; a transversal crossing at the turning point x = A goes through,
// with the closed-form saltation entry (A + a) / (A - a).
TEST(HybridFlow, GrazingCrossingIsReported) {
  const double a = 0.5;
  const Relay system(0.1, a);
  const auto p = system.default_parameters();
  const std::vector<int> sides{1}, surfaces{0};
  EXPECT_THROW(cross_surfaces(system, 0.0, Eigen::Vector2d(a, 0.0), p, sides, surfaces, {}, true),
               NonsmoothFlowError);
  const double amplitude = Relay::amplitude(0.1, a);
  const HybridEvent event =
      cross_surfaces(system, 0.0, Eigen::Vector2d(amplitude, 0.0), p, sides, surfaces, {}, true);
  EXPECT_EQ(event.sides[0], -1);
  EXPECT_NEAR(event.saltation(1, 1), (amplitude + a) / (amplitude - a), 1e-14 * 5.4);
  EXPECT_EQ(event.order_difference, 0.0);
}

// x' = -sign(x) (x' = -1 on x > 0, +1 on x < 0): both fields push towards x = 0, which the flow
// from x = 1 reaches at t = 1 exactly and would then slide along (Filippov). Refused there, by
// name, with the time; a run that ends before it goes through, and counts no crossing.
class HybridSlidingSign final : public AutoDiffHybridSystem<HybridSlidingSign> {
 public:
  HybridSlidingSign() { set_parameter_layout({{"a", {0}}}, {1.0}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"x"}; }
  template <class T, class P>
  void evaluate(double t, const T* z, const P* p, T* dz) const {
    const int side = value_of(z[0]) >= 0.0 ? 1 : -1;
    evaluate_on_sides(t, z, p, dz, &side);
  }
  template <class T, class P>
  void evaluate_on_sides(double, const T*, const P* p, T* dz, const int* sides) const {
    dz[0] = -p[0] * static_cast<double>(sides[0]);
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    g[0] = z[0];
  }
  std::string switching_name(int) const override { return "x = 0"; }
  double switching_gradient(double, const double*, const double*, int, double* h_z) const override {
    h_z[0] = 1.0;
    return 0.0;
  }
};

TEST(HybridFlow, SlidingIsRefusedWhereItBegins) {
  const HybridSlidingSign system;
  const auto p = system.default_parameters();
  Flow flow(system);
  const Eigen::VectorXd start = Eigen::VectorXd::Constant(1, 1.0);
  EXPECT_NEAR(flow.advance(start, p, 0.0, 0.5)[0], 0.5, 1e-12);
  EXPECT_EQ(flow.crossings(), std::vector<int>{0});
  try {
    flow.advance(start, p, 0.0, 2.0);
    FAIL() << "sliding not refused";
  } catch (const NonsmoothFlowError& e) {
    EXPECT_NE(std::string(e.what()).find("sliding"), std::string::npos) << e.what();
    EXPECT_NEAR(e.time(), 1.0, 1e-9);
  }
}

// From x = 0 itself: with a = 1 both fields push towards the surface (sliding from the start:
// refused at t = 0 by name), with a = -1 (x' = sign(x)) both push away from it, and x = t and x =
// -t are both solutions: the one the field at the state points into (x' = 1 there: the system
// reads x = 0 as x > 0) is followed, and said; off the surface, none is said.
TEST(HybridFlow, AStartOnASurfaceWithTwoSolutionsIsSaid) {
  const HybridSlidingSign system;
  const auto sliding = system.default_parameters();
  const auto repelling = system.with_parameter(sliding, 0, -1.0);
  Flow flow(system);
  const Eigen::VectorXd on = Eigen::VectorXd::Zero(1);
  EXPECT_NEAR(flow.advance(on, repelling, 0.0, 1.0)[0], 1.0, 1e-12);
  EXPECT_EQ(flow.two_solutions().rfind("two solutions: at t = 0 the state lies on x = 0, which "
                                       "the fields on both sides push away from",
                                       0),
            0u)
      << flow.two_solutions();
  EXPECT_NE(flow.two_solutions().find("followed: the one into its positive side"),
            std::string::npos)
      << flow.two_solutions();
  EXPECT_NEAR(flow.advance(Eigen::VectorXd::Constant(1, -0.5), repelling, 0.0, 1.0)[0], -1.5,
              1e-12);
  EXPECT_EQ(flow.two_solutions(), "");
  try {
    flow.advance(on, sliding, 0.0, 1.0);
    FAIL() << "sliding from the start not refused";
  } catch (const NonsmoothFlowError& e) {
    EXPECT_EQ(e.time(), 0.0);
    EXPECT_EQ(std::string(e.what()).rfind("sliding: at t = 0", 0), 0u) << e.what();
  }
}

// A ball bouncing under gravity g on a floor x = 0 (crossed downwards only) with restitution e:
// from the floor at v = V it returns after 2 V / g, faster each bounce by e, and the bounces
// accumulate at t* = 2 V / (g (1 - e)) (a Zeno point: then it lies on the floor). Parameters g,
// e.
class BouncingBall final : public AutoDiffHybridSystem<BouncingBall> {
 public:
  BouncingBall() { set_parameter_layout({{"g", {0}}, {"e", {1}}}, {1.0, 0.5}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = z[1];
    dz[1] = T(-p[0]);
  }
  template <class T, class P>
  void evaluate_on_sides(double t, const T* z, const P* p, T* dz, const int*) const {
    evaluate(t, z, p, dz);
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    g[0] = z[0];
  }
  int crossing_direction(int) const override { return -1; }
  std::string switching_name(int) const override { return "x = 0"; }
  double switching_gradient(double, const double*, const double*, int, double* h_z) const override {
    h_z[0] = 1.0;
    h_z[1] = 0.0;
    return 0.0;
  }
  bool has_reset(int) const override { return true; }
  void reset(double, const double* z, const double* p, int, double* z_plus) const override {
    z_plus[0] = z[0];
    z_plus[1] = -p[1] * z[1];
  }
  void reset_jacobian(double, const double*, const double* p, int,
                      Eigen::MatrixXd& r_z) const override {
    r_z = Eigen::Matrix2d{{1.0, 0.0}, {0.0, -p[1]}};
  }
};

// Chattering is refused with the accumulation time, here t* = 2 / (1 - e) = 4 (g = V = 1): the
// ratios are exactly e, so the extrapolation is exact up to the located crossing times (at rtol
// 1e-12, within 1e-9).
// A run that ends before the bounces shrink eight times in a row goes through.
TEST(HybridFlow, ChatteringIsRefusedWithItsAccumulationTime) {
  const BouncingBall system;
  const auto p = system.default_parameters();
  const Eigen::Vector2d floor(0.0, 1.0);
  Flow flow(system, hybrid_flow_settings().front());
  // Four bounces: at t = 2, 3, 3.5, 3.75, and then up at v = 1/16 for 0.05 s more.
  const Eigen::VectorXd z = flow.advance(floor, p, 0.0, 3.8);
  EXPECT_EQ(flow.crossings(), std::vector<int>{4});
  EXPECT_NEAR(z[1], 1.0 / 16 - 0.05, 1e-9);
  try {
    flow.advance(floor, p, 0.0, 10.0);
    FAIL() << "chattering not refused";
  } catch (const NonsmoothFlowError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("chattering: x = 0 crossed 10 times", 0), 0u) << e.what();
    EXPECT_NEAR(e.time(), 4.0, 1e-9) << e.what();
  }
  EXPECT_EQ(flow.crossings(), std::vector<int>{10});
}

// A system with switching surfaces that does not declare their gradients (not a HybridSystem):
// sensitivities across them are refused, not silently wrong.
class HybridUndeclaredSwitch final : public AutoDiffSystem<HybridUndeclaredSwitch> {
 public:
  HybridUndeclaredSwitch() { set_parameter_layout({{"a", {0}}}, {1.0}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"x"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = value_of(z[0]) > 0.0 ? -p[0] * z[0] : T(1.0);
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    g[0] = z[0];
  }
};

TEST(HybridFlow, UndeclaredSurfacesRefuseSensitivities) {
  const HybridUndeclaredSwitch system;
  Flow flow(system);
  EXPECT_THROW(flow.advance_with_sensitivities(Eigen::VectorXd::Constant(1, -1.0),
                                               system.default_parameters(), 0.0, 2.0),
               std::invalid_argument);
  EXPECT_NO_THROW(
      flow.advance(Eigen::VectorXd::Constant(1, -1.0), system.default_parameters(), 0.0, 2.0));
}

}  // namespace
}  // namespace sympathy
