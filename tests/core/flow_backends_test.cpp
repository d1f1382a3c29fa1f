// The flow's three integrators (CVODES's forward-sensitivity module, CVODE on the augmented
// system, ARKODE's ERKStep on it) against exact answers and against each other: the same public
// calls, the same steep-zone caps, switching surfaces and interpolated outputs on each.
#include <gtest/gtest.h>

#include <unsupported/Eigen/MatrixFunctions>

#include "sympathy/core/flow.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::LinearSystem;
using testing::Pulse;

struct Backend {
  std::string name;
  FlowOptions options;
  // Bound on the global relative error over a few time units at rtol 1e-10 (measured on the
  // oscillator below: the multistep methods and Dormand-Prince 2e-11 to 5e-9, Verner 1.6e-8 in
  // 949 steps where Dormand-Prince took 289: ARKODE 6.4.1's Verner 6(5) does as badly without the
  // Flow, see ExplicitTable).
  double error = 1e-8;
};

// Every integrator the options offer, at rtol (atol = rtol / 100).
std::vector<Backend> backends(double rtol) {
  auto make = [rtol](Method method, NonlinearSolver solver, Sensitivities sensitivities,
                     ExplicitTable table = ExplicitTable::DormandPrince) {
    FlowOptions o;
    o.rtol = rtol;
    o.atol = rtol / 100.0;
    o.method = method;
    o.nonlinear_solver = solver;
    o.sensitivities = sensitivities;
    o.explicit_table = table;
    return o;
  };
  return {
      {"forward module, BDF",
       make(Method::BDF, NonlinearSolver::Newton, Sensitivities::ForwardModule)},
      {"forward module, Adams",
       make(Method::Adams, NonlinearSolver::FixedPoint, Sensitivities::ForwardModule)},
      {"augmented, Adams",
       make(Method::Adams, NonlinearSolver::FixedPoint, Sensitivities::Augmented)},
      {"augmented, BDF", make(Method::BDF, NonlinearSolver::Newton, Sensitivities::Augmented)},
      {"ERK, Dormand-Prince", make(Method::ERK, NonlinearSolver::Newton, Sensitivities::Augmented)},
      {"ERK, Verner",
       make(Method::ERK, NonlinearSolver::Newton, Sensitivities::Augmented, ExplicitTable::Verner),
       5e-8},
  };
}

using testing::oscillator_matrix;

// Exact for z' = scale A z at scale = 1: z(t) = expm(A t) z0, dz/dz0 = expm(A t),
// dz/dscale = A t expm(A t) z0, each backend within its Backend::error.
TEST(FlowBackends, TransitionAndParameterSensitivityMatchMatrixExponential) {
  const Eigen::MatrixXd a = oscillator_matrix();
  LinearSystem system(a);
  Eigen::VectorXd z0(3);
  z0 << 1.0, -0.5, 0.25;
  const double t1 = 3.0;
  const Eigen::MatrixXd e = (a * t1).exp();
  const Eigen::VectorXd dz_dscale = a * t1 * e * z0;
  const std::vector<int> scale{system.parameter_index("scale")};
  for (const auto& b : backends(1e-10)) {
    Flow flow(system, b.options);
    const auto r =
        flow.advance_with_sensitivities(z0, system.default_parameters(), 0.0, t1, true, scale);
    EXPECT_LT((r.state - e * z0).norm(), b.error * (e * z0).norm()) << b.name;
    EXPECT_LT((r.transition - e).norm(), b.error * e.norm()) << b.name;
    EXPECT_LT((r.parameter_sensitivities.col(0) - dz_dscale).norm(), b.error * dz_dscale.norm())
        << b.name;
    // Every backend fills its statistics.
    const auto& s = flow.statistics();
    EXPECT_EQ(s.calls, 1) << b.name;
    EXPECT_GT(s.steps, 10) << b.name;
    EXPECT_GT(s.rhs_evaluations, s.steps) << b.name;
    EXPECT_GT(s.variational_evaluations, 0) << b.name;
    // The plain state afterwards, on the same flow (the state alone on every backend).
    EXPECT_LT((flow.advance(z0, system.default_parameters(), 0.0, t1) - e * z0).norm(),
              b.error * (e * z0).norm())
        << b.name;
  }
}

// Outputs interpolated inside steps (CVodeGetDky, CVodeGetSensDky, ERKStepGetDky) agree with the
// exact ones and hence between backends: chosen columns (initial components 2 and 0) and the
// parameter column at times that fall inside steps.
TEST(FlowBackends, SampledSensitivitiesAgree) {
  const Eigen::MatrixXd a = oscillator_matrix();
  LinearSystem system(a);
  Eigen::VectorXd z0(3);
  z0 << 1.0, -0.5, 0.25;
  const std::vector<double> times{0.0, 0.3, 0.7, 1.234, 1.9, 3.0};
  const std::vector<int> components{2, 0};
  const std::vector<int> parameters{system.parameter_index("scale")};
  for (const auto& b : backends(1e-10)) {
    Flow flow(system, b.options);
    std::vector<double> seen;
    flow.sample_with_sensitivities(
        z0, system.default_parameters(), 0.0, times, components, parameters,
        [&](double t, const Eigen::VectorXd& z, const Eigen::MatrixXd& S) {
          seen.push_back(t);
          const Eigen::MatrixXd e = (a * t).exp();
          ASSERT_EQ(S.cols(), 3);
          EXPECT_LT((z - e * z0).norm(), b.error) << b.name << ", t = " << t;
          EXPECT_LT((S.col(0) - e.col(2)).norm(), b.error) << b.name << ", t = " << t;
          EXPECT_LT((S.col(1) - e.col(0)).norm(), b.error) << b.name << ", t = " << t;
          const Eigen::VectorXd dz_dscale = a * t * e * z0;
          EXPECT_LT((S.col(2) - dz_dscale).norm(), b.error * (1.0 + dz_dscale.norm()))
              << b.name << ", t = " << t;
        });
    EXPECT_EQ(seen, times) << b.name;
  }
}

// The steep-zone caps work on every backend, plain and with sensitivities: the pulse's unit area
// is gained within 100 rtol (see Flow.SteepZoneIsResolved); stepped over without them.
TEST(FlowBackends, SteepZoneIsResolvedOnEveryBackend) {
  Pulse system(1e-4, 2);  // two coinciding zones, as symmetric metronomes have
  Eigen::VectorXd z0(4);
  z0 << 1.0, 0.0, 1.0, 0.0;
  for (auto b : backends(1e-9)) {
    b.options.max_steps = 100000;
    Flow resolved(system, b.options);
    const Eigen::VectorXd z = resolved.advance(z0, system.default_parameters(), 0.0, 2.0);
    EXPECT_NEAR(z[1], 1.0, 100 * b.options.rtol) << b.name;
    EXPECT_NEAR(z[3], 1.0, 100 * b.options.rtol) << b.name;
    EXPECT_GT(resolved.statistics().steep_roots, 0) << b.name;
    // With the transition matrix: d q(2) / d u(0) = pulse(1) - pulse(-1) = 0. Its column is
    // driven by the pulse's slope, up to 1/w^2 = 1e8 inside the zone: measured 1e-6 (ERK) to
    // 1.2e-5 (augmented BDF).
    const auto d = resolved.advance_with_sensitivities(z0, system.default_parameters(), 0.0, 2.0);
    EXPECT_NEAR(d.state[1], 1.0, 100 * b.options.rtol) << b.name;
    EXPECT_NEAR(d.transition(1, 0), 0.0, 3e-5) << b.name;
    b.options.resolve_steep_zones = false;
    Flow blind(system, b.options);
    EXPECT_LT(blind.advance(z0, system.default_parameters(), 0.0, 2.0)[1], 0.5) << b.name;
  }
}

// u'' = -u from u = a, u' = 0, and q' = u'^2 exp(-(u/w)^2) / (a w sqrt(pi)): u turns at |u| = a
// and crosses 0 at speed a (u'^2 = a^2 - u^2), so each crossing adds the mean of
// sqrt(1 - u^2/a^2) under the pulse, 1 - w^2 / (4 a^2) up to O(w^4 / a^4), and two periods four
// times that. With a = 0.5 the turns lie within the zone's levels (1, 1/3, ...): u leaves its zone,
// turns inside a band and comes back, which Dormand-Prince steps with the looser caps of the way
// out (Flow).
class SwingThroughPulse final : public AutoDiffSystem<SwingThroughPulse> {
 public:
  SwingThroughPulse(double amplitude, double width) : amplitude_(amplitude), width_(width) {
    set_parameter_layout({}, {});
  }
  int dimension() const override { return 3; }
  std::vector<std::string> state_names() const override { return {"u", "v", "q"}; }
  std::vector<SteepZone> steep_zones(const double* /*p*/) const override {
    return {{0, width_, 1.0}};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    using std::exp;
    const T s = z[0] / width_;
    dz[0] = z[1];
    dz[1] = -z[0];
    dz[2] = z[1] * z[1] * exp(-s * s) / (amplitude_ * width_ * std::sqrt(M_PI));
  }

 private:
  double amplitude_;
  double width_;
};

TEST(FlowBackends, SteepZoneMetAgainAfterATurnIsResolved) {
  const double a = 0.5, w = 1e-4;
  SwingThroughPulse system(a, w);
  Eigen::VectorXd z0(3);
  z0 << a, 0.0, 0.0;
  const double end = 4.0 * M_PI;
  const double gained = 4.0 * (1.0 - w * w / (4.0 * a * a));
  for (auto b : backends(1e-9)) {
    b.options.max_steps = 100000;
    Flow resolved(system, b.options);
    const Eigen::VectorXd z = resolved.advance(z0, system.default_parameters(), 0.0, end);
    // Measured at rtol 1e-9: Dormand-Prince 7e-9, BDF 5e-8, Adams 2.9e-7, Verner 1.1e-6 (as
    // much with the caps kept on the way out: ARKODE's Verner table, see Backend::error).
    EXPECT_NEAR(z[2], gained, 2e-6) << b.name;
    EXPECT_NEAR(z[0], a, 1e-6) << b.name;  // back after two whole periods
    EXPECT_GT(resolved.statistics().steep_roots, 0) << b.name;
    b.options.resolve_steep_zones = false;
    Flow blind(system, b.options);
    EXPECT_LT(blind.advance(z0, system.default_parameters(), 0.0, end)[2], 3.0) << b.name;
  }
}

// x'' = -sign(x), f jumping across x = 0 (a switching surface): from x = 1 at rest, x = 1 - t^2/2
// until t = sqrt(2), the motion symmetric after; period 4 sqrt(2), x = 0 crossed twice a period.
class VShapedWell final : public OdeSystem {
 public:
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  std::vector<std::string> parameter_names() const override { return {}; }
  ParameterValues default_parameters() const override { return ParameterValues(0); }
  double parameter(const ParameterValues&, int) const override { return 0.0; }
  void set_parameter(ParameterValues&, int, double) const override {}
  // Each piece is smooth; the sign is the side the integration started on, kept until the
  // flow stops at the surface and restarts, as a switching model's pieces are.
  void rhs(double, const double* z, const double*, double* dz) const override {
    dz[0] = z[1];
    dz[1] = z[0] > 0.0 ? -1.0 : (z[0] < 0.0 ? 1.0 : (z[1] < 0.0 ? 1.0 : -1.0));
  }
  bool differentiable() const override { return false; }
  void jacobian(double, const double*, const double*, Eigen::MatrixXd& jac) const override {
    jac.setZero(2, 2);
    jac(0, 1) = 1.0;
  }
  void variational_rhs(double, const double*, const double*, int, const double* const*,
                       double* const*, std::span<const int>) const override {
    throw std::logic_error("not differentiable");
  }
  void parameter_derivative(double, const double*, const double*, int, double*) const override {
    throw std::logic_error("no parameters");
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    g[0] = z[0];
  }
};

// Errors measured over two periods at rtol 1e-10: 9e-9 (CVODE), 1.3e-7 (Dormand-Prince, whose
// long steps on the parabolas -- integrated exactly -- leave the root's state to its interpolant).
TEST(FlowBackends, SwitchingSurfacesOnEveryBackend) {
  VShapedWell system;
  Eigen::VectorXd z0(2);
  z0 << 1.0, 0.0;
  const double period = 4.0 * std::sqrt(2.0);
  for (const auto& b : backends(1e-10)) {
    Flow flow(system, b.options);
    const Eigen::VectorXd z = flow.advance(z0, system.default_parameters(), 0.0, 2.0 * period);
    EXPECT_NEAR(z[0], 1.0, 1e-6) << b.name;
    EXPECT_NEAR(z[1], 0.0, 1e-6) << b.name;
    EXPECT_EQ(flow.statistics().switchings, 4) << b.name;
    // A sample between the crossings: x(2) = -(2 - sqrt 2)^2/2 + ... from the exact pieces.
    const double t = 2.0;
    const double s = t - std::sqrt(2.0);  // time since the crossing at speed -sqrt(2)
    const double x = -std::sqrt(2.0) * s + s * s / 2.0;
    flow.sample(z0, system.default_parameters(), 0.0, std::vector<double>{t},
                [&](double, const Eigen::VectorXd& y) { EXPECT_NEAR(y[0], x, 1e-6) << b.name; });
    // The surfaces stay set across calls (each call restarts the integrator).
    flow.reset_statistics();
    flow.advance(z0, system.default_parameters(), 0.0, 2.0 * period);
    EXPECT_EQ(flow.statistics().switchings, 4) << b.name;
  }
}

// The options name what is wrong with a combination no integrator offers.
TEST(FlowBackends, OptionsRejectImpossibleCombinations) {
  FlowOptions erk;
  erk.method = Method::ERK;
  ASSERT_TRUE(erk.validate());
  EXPECT_EQ(erk.validate()->field, "sensitivities");
  erk.sensitivities = Sensitivities::Augmented;
  EXPECT_FALSE(erk.validate());
  FlowOptions quotients;
  quotients.sensitivities = Sensitivities::Augmented;
  quotients.derivatives = Derivatives::DifferenceQuotients;
  ASSERT_TRUE(quotients.validate());
  EXPECT_EQ(quotients.validate()->field, "derivatives");
  LinearSystem system(oscillator_matrix());
  FlowOptions forward_erk;
  forward_erk.method = Method::ERK;
  EXPECT_THROW(Flow(system, forward_erk), std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
