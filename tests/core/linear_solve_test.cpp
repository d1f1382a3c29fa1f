#include "sympathy/core/linear_solve.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace sympathy
