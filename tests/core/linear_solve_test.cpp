#include "sympathy/core/linear_solve.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace sympathy {
namespace {

// A 6 x 6 matrix of rank 4 built as A0 D^-1, with A0 = U diag(s) V^T (two zero singular values)
// and column scales D from 1e-3 to 1e3 (mixed units). Exact answer: the null space is D times
// the span of V's last two columns.
TEST(LinearSolve, NullVectorsSpanTheKnownNullSpaceDespiteMixedUnits) {
  std::srand(21);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qu(Eigen::MatrixXd::Random(6, 6));
  const Eigen::HouseholderQR<Eigen::MatrixXd> qv(Eigen::MatrixXd::Random(6, 6));
  const Eigen::MatrixXd u = qu.householderQ(), v = qv.householderQ();
  Eigen::VectorXd s(6);
  s << 3.0, 2.0, 1.0, 0.5, 0.0, 0.0;
  Eigen::VectorXd d(6);
  d << 1e-3, 1e3, 1.0, 10.0, 0.1, 1e2;
  const Eigen::MatrixXd a0 = u * s.asDiagonal() * v.transpose();
  const Eigen::MatrixXd a = a0 * d.cwiseInverse().asDiagonal();
  const Eigen::SparseMatrix<double> sparse = a.sparseView();

  EXPECT_EQ(rank_deficiency(sparse), 2);
  const Eigen::MatrixXd found = null_vectors(sparse, 2);
  ASSERT_EQ(found.cols(), 2);
  // Each found vector lies in D span(v4, v5): its component outside is below 1e-12.
  const Eigen::MatrixXd exact = d.asDiagonal() * v.rightCols(2);
  const Eigen::HouseholderQR<Eigen::MatrixXd> qe(exact);
  const Eigen::MatrixXd basis = qe.householderQ() * Eigen::MatrixXd::Identity(6, 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(found.col(k).norm(), 1.0, 1e-14);
    const Eigen::VectorXd outside = found.col(k) - basis * (basis.transpose() * found.col(k));
    EXPECT_LT(outside.norm(), 1e-12) << k;
  }
  // And they are independent.
  EXPECT_LT(std::abs(found.col(0).normalized().dot(found.col(1).normalized())), 1.0 - 1e-6);
}

// The shooting Jacobian of the in-phase orbit of eight identical metronomes computed on the whole
// state (cases/row/row8, Adams at rtol 5e-12; 19 x 19, saved to 17 digits), where the
// permutations of the metronomes repeat the difference block's singular value 1.1181e-4
// (relative, after the scaling) fourteen times. The orbit is isolated (the computation in the
// symmetric block and the difference block gives no multiplier but the trivial one within 0.15 of
// 1), so the matrix has full rank: Eigen 3.4's divide-and-conquer SVD gave a smallest singular
// value of 1.0e-7 here at -O2 and -O3, a family that is not there.
TEST(LinearSolve, ClusteredSingularValuesAreNotTakenForARankDeficiency) {
  std::ifstream in(std::string(SYMPATHY_SOURCE_DIR) +
                   "/tests/core/data/row8_whole_state_jacobian.csv");
  ASSERT_TRUE(in.good());
  std::vector<std::vector<double>> rows;
  for (std::string line; std::getline(in, line);) {
    std::stringstream cells(line);
    std::vector<double> row;
    for (std::string cell; std::getline(cells, cell, ',');) row.push_back(std::stod(cell));
    rows.push_back(row);
  }
  const int n = static_cast<int>(rows.size());
  ASSERT_EQ(n, 19);
  Eigen::MatrixXd a(n, n);
  for (int i = 0; i < n; ++i) {
    ASSERT_EQ(static_cast<int>(rows[i].size()), n);
    for (int j = 0; j < n; ++j) a(i, j) = rows[i][j];
  }
  const Eigen::SparseMatrix<double> sparse = a.sparseView(0.0, 0.0);
  EXPECT_EQ(rank_deficiency(sparse, 1e-6), 0);
  // A solve keeps every direction: the residual of A x = b at rounding, where dropping the
  // cluster's spurious direction would leave a part of b unmatched.
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, 1.0, 2.0);
  const LinearSolution s = solve_linear(sparse, b, {});
  EXPECT_EQ(s.rank_deficiency, 0);
  EXPECT_LT((a * s.x - b).cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
}  // namespace sympathy
