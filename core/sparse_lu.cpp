#include "sympathy/core/sparse_lu.hpp"

#include <umfpack.h>

#include <stdexcept>
#include <string>
#include <vector>

namespace sympathy {

SparseLU::SparseLU(const Eigen::SparseMatrix<double>& a) : a_(a) {
  if (a_.rows() != a_.cols()) throw std::invalid_argument("SparseLU: matrix is not square");
  a_.makeCompressed();
  const int n = static_cast<int>(a_.rows());
  double info[UMFPACK_INFO];
  int status = umfpack_di_symbolic(n, n, a_.outerIndexPtr(), a_.innerIndexPtr(), a_.valuePtr(),
                                   &symbolic_, nullptr, info);
  if (status != UMFPACK_OK)
    throw std::runtime_error("UMFPACK symbolic factorization failed, status " +
                             std::to_string(status));
  status = umfpack_di_numeric(a_.outerIndexPtr(), a_.innerIndexPtr(), a_.valuePtr(), symbolic_,
                              &numeric_, nullptr, info);
  if (status != UMFPACK_OK && status != UMFPACK_WARNING_singular_matrix)
    throw std::runtime_error("UMFPACK numeric factorization failed, status " +
                             std::to_string(status));
  rcond_ = status == UMFPACK_WARNING_singular_matrix ? 0.0 : info[UMFPACK_RCOND];
}

SparseLU::~SparseLU() {
  if (numeric_) umfpack_di_free_numeric(&numeric_);
  if (symbolic_) umfpack_di_free_symbolic(&symbolic_);
}

Eigen::VectorXd SparseLU::solve(const Eigen::VectorXd& b) const {
  Eigen::VectorXd x(b.size());
  double info[UMFPACK_INFO];
  const int status = umfpack_di_solve(UMFPACK_A, a_.outerIndexPtr(), a_.innerIndexPtr(),
                                      a_.valuePtr(), x.data(), b.data(), numeric_, nullptr, info);
  if (status != UMFPACK_OK && status != UMFPACK_WARNING_singular_matrix)
    throw std::runtime_error("UMFPACK solve failed, status " + std::to_string(status));
  return x;
}

}  // namespace sympathy
