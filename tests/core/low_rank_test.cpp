// The low-rank-plus-sparse Jacobian and its solver (KLU and Woodbury).
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "sympathy/core/low_rank_jacobian.hpp"
#include "sympathy/core/low_rank_solver.hpp"

namespace sympathy {
namespace {

// A random sparse S (the diagonal present in some columns only, a few entries per column) and
// dense U, W.
LowRankJacobian random_low_rank(int n, int rank, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> row(0, n - 1);
  std::vector<std::pair<int, int>> entries;
  for (int j = 0; j < n; ++j) {
    if (j % 3 != 0) entries.emplace_back(j, j);
    for (int k = 0; k < 2; ++k) entries.emplace_back(row(rng), j);
  }
  LowRankJacobian jac(n, rank, entries);
  for (double& v : jac.values) v = u(rng);
  jac.U = Eigen::MatrixXd::Random(n, rank);
  jac.W = Eigen::MatrixXd::Random(n, rank);
  return jac;
}

TEST(LowRankJacobian, PatternIsSortedWithRepeatsMerged) {
  const LowRankJacobian jac(4, 1, {{2, 1}, {0, 1}, {3, 0}, {2, 1}, {1, 3}});
  EXPECT_EQ(jac.nonzeros(), 4);
  EXPECT_EQ(jac.column_starts, (std::vector<int>{0, 1, 3, 3, 4}));
  EXPECT_EQ(jac.row_indices, (std::vector<int>{3, 0, 2, 1}));
  EXPECT_EQ(jac.position(2, 1), 2);
  EXPECT_EQ(jac.position(1, 1), -1);
  EXPECT_EQ(jac.position(0, 4), -1);
  EXPECT_EQ(jac.rank(), 1);
  EXPECT_THROW(LowRankJacobian(3, 1, {{3, 0}}), std::invalid_argument);
}

TEST(LowRankJacobian, DenseIsSparsePartPlusProduct) {
  std::mt19937 rng(1);
  const LowRankJacobian jac = random_low_rank(7, 2, rng);
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(7, 7);
  for (int j = 0; j < 7; ++j)
    for (int k = jac.column_starts[j]; k < jac.column_starts[j + 1]; ++k)
      s(jac.row_indices[k], j) = jac.values[k];
  EXPECT_EQ(jac.sparse_part(), s);
  EXPECT_LT((jac.dense() - s - jac.U * jac.W.transpose()).cwiseAbs().maxCoeff(), 1e-15);
}

// Expected: a dense LU (Eigen) of the same matrix I - gamma (S + U W^T), for new values in the
// same pattern too. Woodbury's error grows with the condition of I - gamma S (about 1e-15 times
// it, measured), whatever that of I - gamma J: S's entries within [-1, 1] and gamma <= 0.3 keep
// I - gamma S diagonally dominant by columns here.
TEST(LowRankSolver, MatchesDenseSolve) {
  std::mt19937 rng(2);
  for (int rank : {0, 1, 2, 3}) {
    const LowRankJacobian base = random_low_rank(40, rank, rng);
    LowRankJacobian jac = base;
    LowRankSolver solver(jac);
    for (double gamma : {1e-3, 0.05, 0.3}) {
      for (int refill = 0; refill < 3; ++refill) {
        for (std::size_t k = 0; k < jac.values.size(); ++k)
          jac.values[k] = base.values[k] * (1.0 + 0.2 * refill);
        if (refill > 0) jac.U = Eigen::MatrixXd::Random(40, rank);
        ASSERT_TRUE(solver.factor(jac, gamma)) << "rank " << rank << " gamma " << gamma;
        const Eigen::MatrixXd m = Eigen::MatrixXd::Identity(40, 40) - gamma * jac.dense();
        const Eigen::VectorXd b = Eigen::VectorXd::Random(40);
        const Eigen::VectorXd expected = m.partialPivLu().solve(b);
        Eigen::VectorXd x = b;
        solver.solve(x.data());
        EXPECT_LT((x - expected).norm(), 1e-12 * expected.norm())
            << "rank " << rank << " gamma " << gamma << " refill " << refill;
      }
    }
    EXPECT_EQ(solver.factorizations() + solver.refactorizations(), 9);
    EXPECT_GE(solver.factorizations(), 1);
  }
}

// The pivot order kept from gamma = 0.01 (diagonal pivots) gives a zero pivot at gamma = 0.1,
// where I - gamma S = [[0, -0.1], [-0.1, 1]]: factored afresh with pivoting, and solved exactly
// (expected: the 2 x 2 inverse by hand).
TEST(LowRankSolver, PivotsAfreshWhenTheKeptOrderFails) {
  LowRankJacobian jac(2, 0, {{0, 0}, {1, 0}, {0, 1}});
  jac.values = {10.0, 1.0, 1.0};  // S = [[10, 1], [1, 0]]
  LowRankSolver solver(jac);
  ASSERT_TRUE(solver.factor(jac, 0.01));
  ASSERT_TRUE(solver.factor(jac, 0.02));
  EXPECT_EQ(solver.factorizations(), 1);
  EXPECT_EQ(solver.refactorizations(), 1);
  ASSERT_TRUE(solver.factor(jac, 0.1));
  EXPECT_EQ(solver.factorizations(), 2);
  Eigen::Vector2d x(1.0, 2.0);
  solver.solve(x.data());
  // [[0, -0.1], [-0.1, 1]]^-1 = [[-100, -10], [-10, 0]]
  EXPECT_NEAR(x[0], -100.0 - 20.0, 1e-12);
  EXPECT_NEAR(x[1], -10.0, 1e-12);
}

// A singular I - gamma S, and a regular one whose capacitance matrix I - gamma W^T P^-1 U is
// singular (so I - gamma J is): both reported, not solved.
TEST(LowRankSolver, ReportsSingularMatrices) {
  LowRankJacobian jac(3, 1, {{0, 0}, {1, 1}, {2, 2}});
  jac.values = {1.0, 2.0, 0.5};
  LowRankSolver solver(jac);
  EXPECT_FALSE(solver.factor(jac, 0.5));  // 1 - 0.5 * 2 = 0 on the diagonal
  EXPECT_FALSE(solver.factored());
  Eigen::VectorXd x = Eigen::VectorXd::Ones(3);
  EXPECT_THROW(solver.solve(x.data()), std::logic_error);

  jac.values = {0.0, 0.0, 0.0};
  jac.U = Eigen::Vector3d(1.0, 1.0, 0.0);
  jac.W = Eigen::Vector3d(2.0, 3.0, 0.0);  // W^T U = 5: I - 0.2 * 5 = 0
  EXPECT_FALSE(solver.factor(jac, 0.2));
  EXPECT_TRUE(solver.factor(jac, 0.1));
}

}  // namespace
}  // namespace sympathy
