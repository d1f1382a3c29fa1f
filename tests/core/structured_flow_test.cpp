// The flow's structured linear solver (LinearSolver::Structured) on a linear system given with
// its Jacobian in low-rank form, whose exact flow is a matrix exponential.
#include <gtest/gtest.h>

#include <stdexcept>
#include <unsupported/Eigen/MatrixFunctions>

#include "sympathy/core/flow.hpp"
#include "sympathy/core/low_rank_jacobian.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

// z' = A z with A = S + U W^T given in low-rank form; exact flow expm(A t).
class LowRankLinearSystem final : public AutoDiffSystem<LowRankLinearSystem> {
 public:
  explicit LowRankLinearSystem(LowRankJacobian a) : a_(std::move(a)), dense_(a_.dense()) {
    set_parameter_layout({{"scale", {0}}}, {1.0});
  }
  int dimension() const override { return a_.dimension; }
  std::vector<std::string> state_names() const override {
    return std::vector<std::string>(a_.dimension, "z");
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    for (int i = 0; i < dimension(); ++i) {
      T sum(0.0);
      for (int j = 0; j < dimension(); ++j) sum += dense_(i, j) * z[j];
      dz[i] = sum;
    }
  }
  std::optional<LowRankJacobian> low_rank_structure() const override {
    LowRankJacobian shape = a_;
    std::fill(shape.values.begin(), shape.values.end(), 0.0);
    shape.U.setZero();
    shape.W.setZero();
    return shape;
  }
  bool low_rank_jacobian(double, const double*, const double*,
                         LowRankJacobian& out) const override {
    out = a_;
    ++evaluations;
    return true;
  }
  mutable long evaluations = 0;

 private:
  LowRankJacobian a_;
  Eigen::MatrixXd dense_;
};

// A stiff linear system: a fast decaying sparse part and a rank-2 coupling of everything.
LowRankJacobian stiff_low_rank() {
  const int n = 12;
  std::vector<std::pair<int, int>> entries;
  for (int i = 0; i < n; ++i) {
    entries.emplace_back(i, i);
    entries.emplace_back((i + 1) % n, i);
  }
  LowRankJacobian a(n, 2, entries);
  for (int i = 0; i < n; ++i) {
    a.values[a.position(i, i)] = -1.0 - 50.0 * (i % 4);
    a.values[a.position((i + 1) % n, i)] = 0.5;
  }
  for (int i = 0; i < n; ++i) {
    a.U(i, 0) = 0.3 * std::sin(i + 1.0);
    a.U(i, 1) = 0.2 * std::cos(2.0 * i);
    a.W(i, 0) = -0.4 * std::cos(i + 0.5);
    a.W(i, 1) = 0.1 * (i % 3);
  }
  return a;
}

// Expected: expm(A t) z0 and expm(A t) (the transition matrix), analytic.
TEST(Flow, StructuredSolverMatchesMatrixExponential) {
  LowRankLinearSystem system(stiff_low_rank());
  const int n = system.dimension();
  const Eigen::MatrixXd a = stiff_low_rank().dense();
  Eigen::VectorXd z0 = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  FlowOptions o;
  o.linear_solver = LinearSolver::Structured;
  Flow flow(system, o);
  const FlowDerivatives r =
      flow.advance_with_sensitivities(z0, system.default_parameters(), 0.0, 2.0);
  const Eigen::MatrixXd exact = (a * 2.0).exp();
  EXPECT_LT((r.state - exact * z0).cwiseAbs().maxCoeff(), 1e-8 * (exact * z0).norm());
  EXPECT_LT((r.transition - exact).cwiseAbs().maxCoeff(), 1e-8 * exact.norm());
  // CVODES's own counters, as for the dense solver: setups, and Jacobians evaluated for them.
  const auto& st = flow.statistics();
  EXPECT_GT(st.linear_setups, 0);
  EXPECT_GT(st.jacobian_evaluations, 0);
  EXPECT_LE(st.jacobian_evaluations, st.linear_setups);
  EXPECT_EQ(st.jacobian_evaluations, system.evaluations);
}

TEST(Flow, StructuredSolverIsRefusedWithoutLowRankJacobian) {
  testing::LinearSystem plain(Eigen::MatrixXd::Identity(2, 2));
  FlowOptions o;
  o.linear_solver = LinearSolver::Structured;
  try {
    Flow flow(plain, o);
    FAIL() << "a system without a low-rank Jacobian was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("OdeSystem::low_rank_jacobian"), std::string::npos)
        << e.what();
  }
  LowRankLinearSystem system(stiff_low_rank());
  o.derivatives = Derivatives::DifferenceQuotients;
  try {
    Flow flow(system, o);
    FAIL() << "difference quotients were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("difference quotients"), std::string::npos) << e.what();
  }
  EXPECT_EQ(to_string(LinearSolver::Structured), "structured");
}

}  // namespace
}  // namespace sympathy
