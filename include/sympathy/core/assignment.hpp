// The assignment problem: pair each row with one column at the least total cost.
//
// Multipliers are paired by least total squared distance, not greedily (from one continuation
// point to the next; the quotient's to the whole matrix's): two complex pairs that move side by
// side by more than half their gap are matched crosswise by nearest neighbours, but kept apart by
// the total.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace sympathy {

// For a square cost matrix, column[i] of each row i, minimizing the sum of cost(i, column[i])
// (Kuhn-Munkres with potentials, O(n^3)).
std::vector<int> least_cost_assignment(const Eigen::MatrixXd& cost);

}  // namespace sympathy
