#include "sympathy/core/assignment.hpp"

#include <limits>
#include <stdexcept>

namespace sympathy {

// Rows are added one at a time; each addition finds the shortest augmenting path in the reduced
// costs (Dijkstra over columns) and updates the row and column potentials u, v so that reduced
// costs cost(i, j) - u_i - v_j stay non-negative and vanish on the assigned pairs.
std::vector<int> least_cost_assignment(const Eigen::MatrixXd& cost) {
  const int n = static_cast<int>(cost.rows());
  if (cost.cols() != n)
    throw std::invalid_argument("least_cost_assignment: the matrix is not square");
  const double inf = std::numeric_limits<double>::infinity();
  // 1-based, with column 0 a virtual start: row_of[j] is the row assigned to column j.
  std::vector<double> u(n + 1, 0.0), v(n + 1, 0.0);
  std::vector<int> row_of(n + 1, 0), way(n + 1, 0);
  for (int i = 1; i <= n; ++i) {
    row_of[0] = i;
    int j0 = 0;
    std::vector<double> least(n + 1, inf);
    std::vector<bool> used(n + 1, false);
    do {
      used[j0] = true;
      const int i0 = row_of[j0];
      double delta = inf;
      int j1 = 0;
      for (int j = 1; j <= n; ++j) {
        if (used[j]) continue;
        const double reduced = cost(i0 - 1, j - 1) - u[i0] - v[j];
        if (reduced < least[j]) {
          least[j] = reduced;
          way[j] = j0;
        }
        if (least[j] < delta) {
          delta = least[j];
          j1 = j;
        }
      }
      for (int j = 0; j <= n; ++j) {
        if (used[j]) {
          u[row_of[j]] += delta;
          v[j] -= delta;
        } else {
          least[j] -= delta;
        }
      }
      j0 = j1;
    } while (row_of[j0] != 0);
    do {  // flip the augmenting path back to the start
      const int j1 = way[j0];
      row_of[j0] = row_of[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> column(n, -1);
  for (int j = 1; j <= n; ++j)
    if (row_of[j] > 0) column[row_of[j] - 1] = j - 1;
  return column;
}

}  // namespace sympathy
