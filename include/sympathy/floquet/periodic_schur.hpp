// Eigenvalues of a product of matrices by the periodic QR algorithm, never forming the product.
//
// The Floquet multipliers of a multiple-shooting orbit are the eigenvalues of the product of the
// segment transition matrices. Formed explicitly, that product carries rounding errors of size
// eps * |largest multiplier|, which swamp every multiplier smaller than that: with 50 segments
// contracting by exp(-3) each, a multiplier exp(-150) comes out as noise of size 1e-16. The
// periodic QR algorithm (Bojanczyk, Golub and Van Dooren 1992) applies orthogonal
// transformations to each factor separately, making all factors but one upper triangular and
// that one upper triangular too in the limit, so each eigenvalue is a product of diagonal
// entries; rounding errors are then small relative to each factor, and every multiplier keeps
// high relative accuracy whatever its size.
#pragma once

#include <complex>
#include <vector>

#include <Eigen/Dense>

namespace sympathy {

struct ProductEigenvalues {
  std::vector<std::complex<double>> values;  // n eigenvalues, in no particular order
  std::vector<double> log_moduli;  // log|value|, accurate even when |value| under/overflows
  int iterations = 0;              // periodic QR sweeps used
};

// Eigenvalues of the product A[K-1] * ... * A[1] * A[0] of square n x n real matrices (A[0] is
// applied first), by periodic QR on the factors. A value whose modulus is out of the range of
// double comes out as 0 or infinite; its log_moduli entry is still accurate. The arithmetic is
// complex: real eigenvalues carry imaginary parts of rounding size, and conjugate pairs are
// conjugate up to rounding.
// Throws std::invalid_argument for an empty list, non-square or mismatched factors or
// non-finite entries, std::runtime_error if the iteration does not converge.
ProductEigenvalues product_eigenvalues(const std::vector<Eigen::MatrixXd>& factors);

}  // namespace sympathy
