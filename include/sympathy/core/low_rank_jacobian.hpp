// A Jacobian of the form df/dz = S + U W^T: S sparse with a pattern fixed once, U and W dense
// n x rank with a small rank.
//
// Systems where a few shared quantities couple everything have it: write f(z) = phi(z, s(z))
// with s = psi(z) a few shared quantities (e.g. the acceleration of a platform that carries many
// oscillators); then S = dphi/dz at fixed s is sparse, U = dphi/ds and W^T = dpsi/dz. The
// product U W^T is dense, so the Jacobian is, but a linear solver can factor I - gamma S
// sparsely and add the rank-r part by the Woodbury identity (LowRankSolver).
#pragma once

#include <utility>
#include <vector>

#include <Eigen/Dense>

namespace sympathy {

struct LowRankJacobian {
  int dimension = 0;
  // S in compressed sparse columns: the entries of column j are values[k] at rows
  // row_indices[k] for column_starts[j] <= k < column_starts[j + 1], rows increasing.
  std::vector<int> column_starts;
  std::vector<int> row_indices;
  std::vector<double> values;
  Eigen::MatrixXd U;  // n x rank
  Eigen::MatrixXd W;  // n x rank

  LowRankJacobian() = default;
  // The pattern of S from (row, column) pairs in any order, repeats merged; values and U, W zero.
  // Throws std::invalid_argument for an entry outside the n x n matrix.
  LowRankJacobian(int dimension, int rank, std::vector<std::pair<int, int>> entries);

  int rank() const { return static_cast<int>(U.cols()); }
  int nonzeros() const { return static_cast<int>(row_indices.size()); }
  // Where entry (row, column) of S sits in `values`; -1 outside the pattern.
  int position(int row, int column) const;
  // S alone and S + U W^T, as dense matrices (for tests and small systems).
  Eigen::MatrixXd sparse_part() const;
  Eigen::MatrixXd dense() const;
};

}  // namespace sympathy
