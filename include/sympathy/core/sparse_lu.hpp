// Sparse LU factorization by UMFPACK (SuiteSparse), owning its symbolic and numeric objects,
// with UMFPACK's reciprocal condition estimate so callers can tell a singular system.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace sympathy {

class SparseLU {
 public:
  // Factors a square matrix; throws std::runtime_error if UMFPACK fails (not if singular).
  explicit SparseLU(const Eigen::SparseMatrix<double>& a);
  ~SparseLU();
  SparseLU(const SparseLU&) = delete;
  SparseLU& operator=(const SparseLU&) = delete;

  // min |U_ii| / max |U_ii| after UMFPACK's row scaling: 0 for a singular matrix.
  double rcond() const { return rcond_; }
  Eigen::VectorXd solve(const Eigen::VectorXd& b) const;

 private:
  Eigen::SparseMatrix<double> a_;  // compressed, column-major: UMFPACK reads it while solving
  void* symbolic_ = nullptr;
  void* numeric_ = nullptr;
  double rcond_ = 0.0;
};

}  // namespace sympathy
