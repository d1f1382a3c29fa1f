#include "sympathy/core/low_rank_jacobian.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace sympathy {

LowRankJacobian::LowRankJacobian(int n, int rank, std::vector<std::pair<int, int>> entries)
    : dimension(n), U(Eigen::MatrixXd::Zero(n, rank)), W(Eigen::MatrixXd::Zero(n, rank)) {
  if (n < 0 || rank < 0) throw std::invalid_argument("low-rank Jacobian: negative size");
  for (auto [i, j] : entries)
    if (i < 0 || i >= n || j < 0 || j >= n)
      throw std::invalid_argument("low-rank Jacobian: entry (" + std::to_string(i) + ", " +
                                  std::to_string(j) + ") outside a " + std::to_string(n) + " x " +
                                  std::to_string(n) + " matrix");
  std::sort(entries.begin(), entries.end(), [](auto a, auto b) {
    return a.second != b.second ? a.second < b.second : a.first < b.first;
  });
  entries.erase(std::unique(entries.begin(), entries.end()), entries.end());
  column_starts.assign(n + 1, 0);
  row_indices.reserve(entries.size());
  for (auto [i, j] : entries) {
    row_indices.push_back(i);
    ++column_starts[j + 1];
  }
  for (int j = 0; j < n; ++j) column_starts[j + 1] += column_starts[j];
  values.assign(entries.size(), 0.0);
}

int LowRankJacobian::position(int row, int column) const {
  if (column < 0 || column >= dimension) return -1;
  const auto first = row_indices.begin() + column_starts[column];
  const auto last = row_indices.begin() + column_starts[column + 1];
  const auto it = std::lower_bound(first, last, row);
  return it != last && *it == row ? static_cast<int>(it - row_indices.begin()) : -1;
}

Eigen::MatrixXd LowRankJacobian::sparse_part() const {
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(dimension, dimension);
  for (int j = 0; j < dimension; ++j)
    for (int k = column_starts[j]; k < column_starts[j + 1]; ++k) s(row_indices[k], j) += values[k];
  return s;
}

Eigen::MatrixXd LowRankJacobian::dense() const {
  return sparse_part() + U * W.transpose();
}

}  // namespace sympathy
