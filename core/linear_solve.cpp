#include "core/linear_solve.hpp"

#include <stdexcept>

#include "core/sparse_lu.hpp"

namespace sympathy {

namespace {

Eigen::VectorXd column_scale(const Eigen::SparseMatrix<double>& a) {
  Eigen::VectorXd scale(a.cols());
  for (int j = 0; j < a.cols(); ++j) {
    const double norm = a.col(j).norm();
    scale[j] = norm > 0.0 ? 1.0 / norm : 1.0;
  }
  return scale;
}

// An SVD, not Eigen 3.4's CompleteOrthogonalDecomposition: its solve reads uninitialized
// workspace on rank-deficient matrices (seen with valgrind), which is the case that matters here.
Eigen::BDCSVD<Eigen::MatrixXd> scaled_svd(const Eigen::SparseMatrix<double>& a,
                                          const Eigen::VectorXd& scale, double rank_tolerance,
                                          bool vectors) {
  Eigen::BDCSVD<Eigen::MatrixXd> svd((a * scale.asDiagonal()).toDense(),
                                     vectors ? Eigen::ComputeThinU | Eigen::ComputeThinV : 0);
  svd.setThreshold(rank_tolerance);
  return svd;
}

}  // namespace

int rank_deficiency(const Eigen::SparseMatrix<double>& a, double rank_tolerance) {
  const auto svd = scaled_svd(a, column_scale(a), rank_tolerance, false);
  return static_cast<int>(std::min(a.rows(), a.cols()) - svd.rank());
}

LinearSolution solve_linear(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b,
                            const LinearSolveOptions& options) {
  if (a.rows() != a.cols() || a.rows() != b.size())
    throw std::invalid_argument("solve_linear: sizes do not match");
  const int n = static_cast<int>(a.cols());
  const Eigen::VectorXd scale = column_scale(a);
  const Eigen::SparseMatrix<double> scaled = a * scale.asDiagonal();
  LinearSolution s;
  if (options.prefer_sparse) {
    SparseLU lu(scaled);
    if (lu.rcond() > options.sparse_rcond_limit) {
      s.x = scale.asDiagonal() * lu.solve(b);
      s.sparse = true;
      return s;
    }
  }
  const auto svd = scaled_svd(a, scale, options.rank_tolerance, true);
  s.rank_deficiency = n - static_cast<int>(svd.rank());
  s.x = scale.asDiagonal() * svd.solve(b);  // the minimum-norm solution
  return s;
}

}  // namespace sympathy
