#include "sympathy/core/linear_solve.hpp"

#include <cmath>
#include <stdexcept>

#include "sympathy/core/sparse_lu.hpp"

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

// Row scales of a (already column-scaled) matrix: each row to unit norm.
Eigen::VectorXd row_scale(const Eigen::SparseMatrix<double>& a) {
  Eigen::VectorXd norm2 = Eigen::VectorXd::Zero(a.rows());
  for (int k = 0; k < a.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator i(a, k); i; ++i)
      norm2[i.row()] += i.value() * i.value();
  Eigen::VectorXd scale(a.rows());
  for (int i = 0; i < a.rows(); ++i) scale[i] = norm2[i] > 0.0 ? 1.0 / std::sqrt(norm2[i]) : 1.0;
  return scale;
}

// An SVD, not Eigen 3.4's CompleteOrthogonalDecomposition: its solve reads uninitialized
// workspace on rank-deficient matrices (seen with valgrind), which is the case that matters here.
// One-sided Jacobi, not Eigen 3.4's divide-and-conquer BDCSVD (which it uses from 16 columns):
// on the whole-state shooting Jacobian of eight identical metronomes (19 columns, a singular
// value of 1.1e-4 repeated fourteen times) BDCSVD returned a smallest one of 1.0e-7 for one
// integration tolerance in five, a family that is not there, and multipliers 0.05 off.
// Jacobi's cost, O(n^3) a few sweeps over, is small beside the sensitivities' integration that
// made the matrix (n^2 equations over a period).
Eigen::JacobiSVD<Eigen::MatrixXd> scaled_svd(const Eigen::SparseMatrix<double>& scaled,
                                             double rank_tolerance, int vectors) {
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled.toDense(), vectors);
  if (rank_tolerance > 0.0) svd.setThreshold(rank_tolerance);
  return svd;
}

}  // namespace

int rank_deficiency(const Eigen::SparseMatrix<double>& a, double rank_tolerance) {
  const Eigen::SparseMatrix<double> columns = a * column_scale(a).asDiagonal();
  const Eigen::SparseMatrix<double> scaled = row_scale(columns).asDiagonal() * columns;
  const auto svd = scaled_svd(scaled, rank_tolerance, 0);
  return static_cast<int>(std::min(a.rows(), a.cols()) - svd.rank());
}

Eigen::MatrixXd null_vectors(const Eigen::SparseMatrix<double>& a, int dimension) {
  const Eigen::VectorXd columns = column_scale(a);
  const Eigen::SparseMatrix<double> partly = a * columns.asDiagonal();
  const Eigen::SparseMatrix<double> scaled = row_scale(partly).asDiagonal() * partly;
  const auto svd = scaled_svd(scaled, 0.0, Eigen::ComputeFullV);
  const int n = static_cast<int>(a.cols());
  Eigen::MatrixXd v(n, dimension);
  for (int k = 0; k < dimension; ++k)
    v.col(k) = (columns.asDiagonal() * svd.matrixV().col(n - 1 - k)).normalized();
  return v;
}

LinearSolution solve_linear(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b,
                            const LinearSolveOptions& options) {
  if (a.rows() != a.cols() || a.rows() != b.size())
    throw std::invalid_argument("solve_linear: sizes do not match");
  const int n = static_cast<int>(a.cols());
  // Solve (R A C) y = R b and x = C y: the same x, with rank decided free of units.
  const Eigen::VectorXd columns = column_scale(a);
  const Eigen::SparseMatrix<double> partly = a * columns.asDiagonal();
  const Eigen::VectorXd rows = row_scale(partly);
  const Eigen::SparseMatrix<double> scaled = rows.asDiagonal() * partly;
  const Eigen::VectorXd rb = rows.asDiagonal() * b;
  LinearSolution s;
  if (options.prefer_sparse) {
    SparseLU lu(scaled);
    if (lu.rcond() > options.sparse_rcond_limit) {
      s.x = columns.asDiagonal() * lu.solve(rb);
      s.sparse = true;
      return s;
    }
  }
  const auto svd =
      scaled_svd(scaled, options.rank_tolerance, Eigen::ComputeThinU | Eigen::ComputeThinV);
  s.rank_deficiency = n - static_cast<int>(svd.rank());
  s.x = columns.asDiagonal() * svd.solve(rb);  // minimum norm in the column-scaled variables
  return s;
}

}  // namespace sympathy
