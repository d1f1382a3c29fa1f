#include "sympathy/core/flow.hpp"

#include <gtest/gtest.h>

#include <unsupported/Eigen/MatrixFunctions>

#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::BlowUp;
using testing::Decay;
using testing::LinearSystem;
using testing::Pulse;

using testing::oscillator_matrix;

// Exact: z(t) = expm(A t) z0.
TEST(Flow, LinearSystemMatchesMatrixExponential) {
  const Eigen::MatrixXd a = oscillator_matrix();
  LinearSystem system(a);
  Eigen::VectorXd z0(3);
  z0 << 1.0, -0.5, 0.25;
  for (Method method : {Method::BDF, Method::Adams}) {
    FlowOptions o;
    o.method = method;
    o.nonlinear_solver =
        method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
    Flow flow(system, o);
    const Eigen::VectorXd z = flow.advance(z0, system.default_parameters(), 0.0, 3.0);
    const Eigen::VectorXd exact = (a * 3.0).exp() * z0;
    EXPECT_LT((z - exact).norm(), 1e-8 * exact.norm()) << to_string(method);
  }
}

// Exact: dz(t)/dz0 = expm(A t), for dense and KLU linear solvers and both correctors.
TEST(Flow, TransitionMatrixMatchesMatrixExponential) {
  const Eigen::MatrixXd a = oscillator_matrix();
  LinearSystem system(a);
  const Eigen::VectorXd z0 = Eigen::VectorXd::Constant(3, 0.3);
  const Eigen::MatrixXd exact = (a * 2.0).exp();
  for (LinearSolver solver : {LinearSolver::Dense, LinearSolver::KLU}) {
    for (SensitivityCorrector corrector :
         {SensitivityCorrector::Staggered, SensitivityCorrector::Simultaneous}) {
      FlowOptions o;
      o.linear_solver = solver;
      o.corrector = corrector;
      Flow flow(system, o);
      const auto r = flow.advance_with_sensitivities(z0, system.default_parameters(), 0.0, 2.0);
      EXPECT_LT((r.transition - exact).norm(), 1e-8 * exact.norm()) << to_string(solver);
      EXPECT_LT((r.state - exact * z0).norm(), 1e-9);
    }
  }
}

// Exact: z = z0 exp(-a t), dz/da = -t z0 exp(-a t); state and parameter columns together.
TEST(Flow, ParameterSensitivityOfDecay) {
  Decay system(0.7);
  Flow flow(system);
  Eigen::VectorXd z0(1);
  z0 << 2.0;
  const int a = system.parameter_index("a");
  const ParameterValues values = system.default_parameters();
  const auto r = flow.advance_with_sensitivities(z0, values, 0.0, 1.5, true, std::vector<int>{a});
  const double e = std::exp(-0.7 * 1.5);
  EXPECT_NEAR(r.state[0], 2.0 * e, 1e-10);
  EXPECT_NEAR(r.transition(0, 0), e, 1e-10);
  EXPECT_NEAR(r.parameter_sensitivities(0, 0), -1.5 * 2.0 * e, 1e-9);
  // Parameter column alone, without the state columns.
  const auto p = flow.advance_with_sensitivities(z0, values, 0.0, 1.5, false, std::vector<int>{a});
  EXPECT_EQ(p.transition.size(), 0);
  EXPECT_NEAR(p.parameter_sensitivities(0, 0), -1.5 * 2.0 * e, 1e-9);
}

// Global errors are about ten times rtol (default 1e-10), hence the 1e-8 tolerances below.
// Calls alternate between sensitivity settings on one Flow; each gives its own exact answer.
TEST(Flow, ReusedAcrossCallsWithDifferentRequests) {
  Decay system(1.1);
  Flow flow(system);
  Eigen::VectorXd z0(1);
  z0 << 1.0;
  const ParameterValues p = system.default_parameters();
  for (int round = 0; round < 3; ++round) {
    EXPECT_NEAR(flow.advance(z0, p, 0.0, 1.0)[0], std::exp(-1.1), 1e-8);
    const auto r = flow.advance_with_sensitivities(z0, p, 0.0, 2.0);
    EXPECT_NEAR(r.transition(0, 0), std::exp(-2.2), 1e-8);
    const auto q = flow.advance_with_sensitivities(z0, p, 0.0, 2.0, true, std::vector<int>{0});
    EXPECT_NEAR(q.parameter_sensitivities(0, 0), -2.0 * std::exp(-2.2), 1e-8);
  }
  EXPECT_EQ(flow.statistics().calls, 9);
  EXPECT_GT(flow.statistics().steps, 0);
  EXPECT_GT(flow.statistics().variational_evaluations, 0);
}

// One integration, sensitivities interpolated at the sample times. Exact for z' = scale A z at
// scale = 1: z = expm(A t) z0, dz/dz0[c] = column c of expm(A t), dz/dscale = A t expm(A t) z0.
TEST(Flow, SampleWithSensitivitiesMatchesMatrixExponential) {
  const Eigen::MatrixXd a = oscillator_matrix();
  LinearSystem system(a);
  Flow flow(system);
  Eigen::VectorXd z0(3);
  z0 << 1.0, -0.5, 0.25;
  const std::vector<double> times{0.0, 0.3, 0.7, 1.9, 3.0};
  const std::vector<int> components{2, 0};
  const std::vector<int> parameters{system.parameter_index("scale")};
  const ParameterValues p = system.default_parameters();
  std::vector<double> seen;
  flow.sample_with_sensitivities(
      z0, p, 0.0, times, components, parameters,
      [&](double t, const Eigen::VectorXd& z, const Eigen::MatrixXd& S) {
        seen.push_back(t);
        const Eigen::MatrixXd e = (a * t).exp();
        ASSERT_EQ(S.cols(), 3);
        EXPECT_LT((z - e * z0).norm(), 1e-8) << "t = " << t;
        EXPECT_LT((S.col(0) - e.col(2)).norm(), 1e-8) << "t = " << t;
        EXPECT_LT((S.col(1) - e.col(0)).norm(), 1e-8) << "t = " << t;
        const Eigen::VectorXd dz_dscale = a * t * e * z0;
        EXPECT_LT((S.col(2) - dz_dscale).norm(), 1e-8 * (1.0 + dz_dscale.norm())) << "t = " << t;
      });
  EXPECT_EQ(seen, times);
  EXPECT_THROW(flow.sample_with_sensitivities(z0, p, 0.0, std::vector<double>{1.0, 0.5}, components,
                                              parameters, [](double, auto&, auto&) {}),
               std::invalid_argument);
  EXPECT_THROW(flow.sample_with_sensitivities(z0, p, 0.0, times, std::vector<int>{3}, parameters,
                                              [](double, auto&, auto&) {}),
               std::invalid_argument);
}

// The observer sees exactly the requested times, with the exact states.
TEST(Flow, SampleAtRequestedTimes) {
  Decay system(0.5);
  Flow flow(system);
  Eigen::VectorXd z0(1);
  z0 << 1.0;
  std::vector<double> times{0.0, 0.1, 0.25, 1.0, 4.0};
  const ParameterValues p = system.default_parameters();
  std::vector<double> seen;
  flow.sample(z0, p, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
    seen.push_back(t);
    EXPECT_NEAR(z[0], std::exp(-0.5 * t), 1e-8) << "t = " << t;
  });
  EXPECT_EQ(seen, times);
  EXPECT_THROW(flow.sample(z0, p, 0.0, std::vector<double>{1.0, 0.5}, [](double, auto&) {}),
               std::invalid_argument);
}

// A blow-up is an IntegrationError that says when, not a crash or a silent wrong answer.
TEST(Flow, BlowUpIsReportedWithItsTime) {
  BlowUp system;
  FlowOptions o;
  o.max_steps = 20000;  // fail fast: steps shrink without end near the singularity
  Flow flow(system, o);
  Eigen::VectorXd z0(1);
  z0 << 1.0;
  const ParameterValues p = system.default_parameters();
  try {
    flow.advance(z0, p, 0.0, 2.0);
    FAIL() << "expected an IntegrationError";
  } catch (const IntegrationError& e) {
    EXPECT_NEAR(e.time(), 1.0, 1e-3);  // z = 1/(1 - t)
    EXPECT_NE(std::string(e.what()).find("CVode"), std::string::npos);
  }
  // The failed call's work is counted (a failed simulation reports its steps).
  EXPECT_GT(flow.statistics().steps, 100);
  // The same Flow works again afterwards.
  z0[0] = 0.1;
  EXPECT_NEAR(flow.advance(z0, p, 0.0, 1.0)[0], 0.1 / 0.9, 1e-9);
}

// The step limit is per output interval when a run samples its solution (issue 32: a simulation
// of 2000 s stopped at t = 1017 with the limit per run): with 300 steps allowed, sampling every
// 1 s to t = 200 (thousands of steps in all) runs to the end, exact to 1e-7 (expm), while one
// call to t = 200 without samples stops at the limit.
TEST(Flow, StepLimitIsPerOutputInterval) {
  const Eigen::MatrixXd a = oscillator_matrix();
  LinearSystem system(a);
  const Eigen::VectorXd z0 = Eigen::VectorXd::Constant(3, 0.3);
  FlowOptions o;
  o.max_steps = 300;
  Flow flow(system, o);
  std::vector<double> times;
  for (int i = 0; i <= 200; ++i) times.push_back(i);
  Eigen::VectorXd last;
  flow.sample_until(z0, system.default_parameters(), 0.0, times, [&](double, const auto& z) {
    last = z;
    return false;
  });
  EXPECT_GT(flow.statistics().steps, 2 * o.max_steps);
  const Eigen::VectorXd exact = (a * 200.0).exp() * z0;
  EXPECT_LT((last - exact).norm(), 1e-7 * (1 + exact.norm()));
  EXPECT_THROW(flow.advance(z0, system.default_parameters(), 0.0, 200.0), IntegrationError);
}

// z' = sqrt(a - t): not finite past t = a. The integrator retries ever smaller steps and gives up
// at t = a; the failure says the right-hand side is not finite, where and at what state and
// parameters (issue 32: only a CVODES code), with every method.
class RootOfTimeLeft final : public AutoDiffSystem<RootOfTimeLeft> {
 public:
  RootOfTimeLeft() { set_parameter_layout({{"a", {0}}}, {1.0}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"z"}; }
  bool autonomous() const override { return false; }
  template <class T, class P>
  void evaluate(double t, const T*, const P* p, T* dz) const {
    using std::sqrt;
    dz[0] = T(sqrt(p[0] - t));
  }
};

TEST(Flow, NonFiniteRightHandSideIsReportedAsSuch) {
  RootOfTimeLeft system;
  for (Method method : {Method::BDF, Method::Adams, Method::ERK}) {
    FlowOptions o;
    o.method = method;
    o.nonlinear_solver =
        method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
    if (method == Method::ERK) o.sensitivities = Sensitivities::Augmented;
    o.max_steps = 20000;  // the steps shrink against t = 1 until a limit stops them
    Flow flow(system, o);
    try {
      flow.advance(Eigen::VectorXd::Ones(1), system.default_parameters(), 0.0, 3.0);
      ADD_FAILURE() << to_string(method) << ": no IntegrationError";
    } catch (const IntegrationError& e) {
      const std::string what = e.what();
      EXPECT_NEAR(e.time(), 1.0, 1e-6) << what;
      EXPECT_NE(what.find("the right-hand side is not finite at t = 1"), std::string::npos)
          << to_string(method) << ": " << what;
      EXPECT_NE(what.find("dz/dt = "), std::string::npos) << what;
      EXPECT_NE(what.find("and parameters a = 1"), std::string::npos) << what;
    }
  }
}

// Sample times: multiples of dt up to t_end, and t_end itself where dt does not divide it (exact
// in binary for 0.25; 0.3 k rounds, so to 1e-15).
TEST(Flow, SampleTimesEndAtTheEnd) {
  EXPECT_EQ(sample_times(1.0, 0.25), (std::vector<double>{0.0, 0.25, 0.5, 0.75, 1.0}));
  const auto t = sample_times(1.0, 0.3);
  ASSERT_EQ(t.size(), 5u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(t[k], 0.3 * k, 1e-15);
  EXPECT_EQ(t.back(), 1.0);
  EXPECT_EQ(sample_times(0.5, 0.5), (std::vector<double>{0.0, 0.5}));
}

TEST(Flow, RejectsBadInput) {
  Decay system(1.0);
  Flow flow(system);
  const ParameterValues p = system.default_parameters();
  EXPECT_THROW(flow.advance(Eigen::VectorXd::Zero(2), p, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(flow.advance(Eigen::VectorXd::Zero(1), p, 1.0, 0.0), std::invalid_argument);
  Eigen::VectorXd bad(1);
  bad << std::nan("");
  EXPECT_THROW(flow.advance(bad, p, 0.0, 1.0), std::invalid_argument);
  FlowOptions o;
  o.rtol = -1.0;
  EXPECT_THROW(Flow(system, o), std::invalid_argument);
}

// A unit-area pulse of width 1e-4 as u crosses 0: resolved, q gains exactly 1 (erf(1e4) = 1)
// up to the integrator's error, which falls with the tolerance (measured: BDF about 30 rtol,
// Adams about 2 rtol); left to error control, the integrator steps straight over the pulse and
// q gains nothing.
TEST(Flow, SteepZoneIsResolved) {
  Pulse system(1e-4);
  Eigen::VectorXd z0(2);
  z0 << 1.0, 0.0;
  for (Method method : {Method::BDF, Method::Adams}) {
    for (double rtol : {1e-8, 1e-10}) {
      FlowOptions o;
      o.method = method;
      o.nonlinear_solver =
          method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
      o.rtol = rtol;
      Flow resolved(system, o);
      EXPECT_NEAR(resolved.advance(z0, system.default_parameters(), 0.0, 2.0)[1], 1.0, 100 * rtol)
          << to_string(method);
      EXPECT_GT(resolved.statistics().steep_roots, 0);
      o.resolve_steep_zones = false;
      Flow blind(system, o);
      EXPECT_LT(blind.advance(z0, system.default_parameters(), 0.0, 2.0)[1], 0.5)
          << to_string(method);
    }
  }
}

// Two identical zones crossed at the same instants (as symmetric metronomes do): both pulses are
// resolved, each gain 1 within 100 rtol, and the run ends. (Root functions on the zones' levels
// made CVODES return the same root at the same time over and over; the bands read off the state
// after each step have no such trouble.)
TEST(Flow, CoincidingSteepZonesAreBothResolved) {
  Pulse system(1e-4, 2);
  Eigen::VectorXd z0(4);
  z0 << 1.0, 0.0, 1.0, 0.0;
  FlowOptions o;
  o.rtol = 1e-10;
  o.max_steps = 100000;
  Flow flow(system, o);
  const Eigen::VectorXd z = flow.advance(z0, system.default_parameters(), 0.0, 2.0);
  EXPECT_NEAR(z[1], 1.0, 100 * o.rtol);
  EXPECT_NEAR(z[3], 1.0, 100 * o.rtol);
  EXPECT_GT(flow.statistics().steep_roots, 0);
}

}  // namespace
}  // namespace sympathy

namespace sympathy {
namespace {

// CVODES's difference quotients give the same transition matrix (exact: expm(A t)) to their
// own accuracy, and refuse parameter columns.
TEST(Flow, DifferenceQuotientDerivatives) {
  Eigen::MatrixXd a(2, 2);
  a << 0.0, 1.0, -4.0, -0.3;
  testing::LinearSystem system(a);
  FlowOptions o;
  o.derivatives = Derivatives::DifferenceQuotients;
  Flow flow(system, o);
  const Eigen::VectorXd z0 = Eigen::VectorXd::Constant(2, 0.5);
  const Eigen::MatrixXd exact = (a * 2.0).exp();
  const ParameterValues p = system.default_parameters();
  EXPECT_LT((flow.advance_with_sensitivities(z0, p, 0.0, 2.0).transition - exact).norm(),
            1e-6 * exact.norm());
  EXPECT_THROW(flow.advance_with_sensitivities(z0, p, 0.0, 2.0, true, std::vector<int>{0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
