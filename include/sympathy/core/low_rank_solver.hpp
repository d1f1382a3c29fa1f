// Solves (I - gamma J) x = b for J = S + U W^T (LowRankJacobian): the Newton matrix of an
// implicit integrator when the Jacobian is sparse plus a dense part of small rank r.
//
// P = I - gamma S is factored sparsely by KLU (SuiteSparse): the pattern is analyzed (ordered)
// once; each factor() refactors in the last pivot order, or factors afresh with partial pivoting
// when KLU's condition estimate says the old order has become poor.
// By the Woodbury identity, with Z = P^{-1} U (r sparse solves) and the r x r capacitance
// matrix K = I_r - gamma W^T Z,
//   (P - gamma U W^T)^{-1} b = y + gamma Z K^{-1} W^T y,   y = P^{-1} b,
// so a solve costs one sparse solve and O(n r). A dense LU would cost O(n^3) per factorization
// and O(n^2) per solve.
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/low_rank_jacobian.hpp"

namespace sympathy {

class LowRankSolver {
 public:
  // Analyzes the pattern of I - gamma S for Jacobians shaped like `structure`.
  explicit LowRankSolver(const LowRankJacobian& structure);
  ~LowRankSolver();
  LowRankSolver(const LowRankSolver&) = delete;
  LowRankSolver& operator=(const LowRankSolver&) = delete;

  // Factors I - gamma J for `jacobian` (the structure's pattern and rank). False when
  // I - gamma S or the capacitance matrix is numerically singular; solve() is then unusable
  // until a factor() succeeds.
  bool factor(const LowRankJacobian& jacobian, double gamma);
  // x := (I - gamma J)^{-1} x, for the last successful factor().
  void solve(double* x);
  bool factored() const { return factored_; }
  // Factorizations with pivoting, and refactorizations in a kept pivot order, since
  // construction.
  long factorizations() const { return factorizations_; }
  long refactorizations() const { return refactorizations_; }

 private:
  struct Klu;
  int n_ = 0;
  int rank_ = 0;
  // P = I - gamma S in compressed sparse columns: S's pattern plus the diagonal.
  std::vector<int> column_starts_, row_indices_;
  std::vector<double> values_;
  std::vector<int> from_s_;    // position in P of each entry of S
  std::vector<int> diagonal_;  // position in P of each diagonal entry
  std::unique_ptr<Klu> klu_;
  Eigen::MatrixXd Z_, W_;
  Eigen::MatrixXd capacitance_, capacitance_inverse_;
  Eigen::PartialPivLU<Eigen::MatrixXd> capacitance_lu_;
  Eigen::VectorXd projected_, small_;  // r-vector scratch
  double pivoted_rcond_ = 0.0;         // KLU's estimate at the last factorization with pivoting
  bool factored_ = false;
  long factorizations_ = 0;
  long refactorizations_ = 0;
};

}  // namespace sympathy
