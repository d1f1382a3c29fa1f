// Test functions that vanish where a periodic orbit bifurcates and are regular there, so that a
// bifurcation can be continued in two parameters by Newton on the orbit's equations plus one
// more: the minimally augmented systems of Govaerts (Numerical Methods for Bifurcations of
// Dynamical Equilibria, SIAM 2000, ch. 4) on the monodromy's block where the critical
// multipliers live.
//
// A real multiplier at +1 or -1 makes B - I or B + I singular; a pair on the unit circle,
// mu and conj(mu), makes the second compound of B (its exterior square, whose eigenvalues are
// the products mu_i mu_j, i < j) minus I singular, one real condition for the pair without its
// angle as an unknown. That condition also holds at a neutral saddle (real mu and 1 / mu): the
// curve's critical pair says which it is. The determinant would vanish too, but at the rate of
// every other eigenvalue at once; the bordered value g below has derivative -w^T dA v, as
// regular as the crossing itself.
#pragma once

#include <Eigen/Dense>

namespace sympathy {

// The exterior square of a q x q matrix: C_(ij),(kl) = B_ik B_jl - B_il B_jk over i < j, k < l
// (in lexicographic order), q (q - 1) / 2 square; its eigenvalues are mu_i mu_j, i < j.
Eigen::MatrixXd exterior_square(const Eigen::MatrixXd& b);

// g(A) from the bordered system [A b; c^T 0] [v; g] = [0; 1], with borders b and c near A's left
// and right null vectors: g = 0 exactly where A is singular, and g is smooth in A.
class BorderedSingularity {
 public:
  // Borders from the singular vectors of a's smallest singular value.
  explicit BorderedSingularity(const Eigen::MatrixXd& a);

  struct Value {
    double g = 0.0;
    Eigen::VectorXd v;  // right: c^T v = 1; A v = -g b
    Eigen::VectorXd w;  // left:  b^T w = 1; A^T w = -g c
    // dg = -w^T dA v: the rate at which g moves with a change dA of A. For a change that moves
    // only the critical eigenvalue by d_lambda, dg = -(w^T v) d_lambda.
    double eigenvalue_rate() const { return std::abs(w.dot(v)); }
  };
  Value value(const Eigen::MatrixXd& a) const;
  // Borders moved to the null vectors of `a` (v and w of its value, normalised): they stay
  // nearly null along a curve, which keeps the bordered system well conditioned.
  void update(const Eigen::MatrixXd& a);

 private:
  Eigen::VectorXd b_, c_;
};

}  // namespace sympathy
