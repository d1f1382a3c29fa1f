#include "sympathy/floquet/periodic_schur.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace sympathy {
namespace {

using cd = std::complex<double>;
using Eigen::MatrixXcd;

constexpr double kEps = std::numeric_limits<double>::epsilon();

// G = [c s; -conj(s) c], c real: a plane rotation acting on rows (i, i+1) from the left.
struct Rotation {
  double c = 1.0;
  cd s = 0.0;
};

// The rotation with G [a; b] = [r; 0].
Rotation annihilate(cd a, cd b) {
  const double na = std::abs(a), nb = std::abs(b);
  if (nb == 0.0) return {};
  if (na == 0.0) return {0.0, 1.0};
  const double norm = std::hypot(na, nb);
  return {na / norm, (a / na) * std::conj(b) / norm};
}

// M <- G M on rows (i, i+1), columns c0..c1.
void rotate_rows(MatrixXcd& m, int i, const Rotation& g, int c0, int c1) {
  for (int j = c0; j <= c1; ++j) {
    const cd x = m(i, j), y = m(i + 1, j);
    m(i, j) = g.c * x + g.s * y;
    m(i + 1, j) = -std::conj(g.s) * x + g.c * y;
  }
}

// M <- M G^* on columns (i, i+1), rows r0..r1: the same change of basis seen from the factor on
// the other side, so the product of the two is unchanged.
void rotate_columns(MatrixXcd& m, int i, const Rotation& g, int r0, int r1) {
  for (int j = r0; j <= r1; ++j) {
    const cd u = m(j, i), v = m(j, i + 1);
    m(j, i) = g.c * u + std::conj(g.s) * v;
    m(j, i + 1) = -g.s * u + g.c * v;
  }
}

// A complex number as mantissa * 2^exponent, so that long products neither under- nor overflow.
struct ScaledComplex {
  cd mantissa = 1.0;
  int exponent = 0;

  void multiply(cd x) {
    mantissa *= x;
    if (mantissa == 0.0) return;
    int e = 0;
    std::frexp(std::abs(mantissa), &e);
    mantissa = {std::ldexp(mantissa.real(), -e), std::ldexp(mantissa.imag(), -e)};
    exponent += e;
  }
  double log_modulus() const {
    if (mantissa == 0.0) return -std::numeric_limits<double>::infinity();
    return std::log(std::abs(mantissa)) + exponent * std::numbers::ln2;
  }
  // The value, or 0 / infinity with the right argument when out of range.
  cd value() const {
    return {std::ldexp(mantissa.real(), exponent), std::ldexp(mantissa.imag(), exponent)};
  }
};

// Scales m to max-modulus 1, accumulating the log of the scale: the trailing block of a long
// product would otherwise under- or overflow.
void normalize(MatrixXcd& m, double& log_scale) {
  const double s = m.cwiseAbs().maxCoeff();
  if (s == 0.0 || !std::isfinite(s)) return;
  m /= s;
  log_scale += std::log(s);
}

// Factors in periodic Hessenberg-triangular form: with unitary Z_0..Z_{K-1} (Z_K = Z_0),
// t_[k] = Z_{k+1}^* A_k Z_k is upper triangular (k < K-1) and h_ = Z_0^* A_{K-1} Z_{K-1} is
// upper Hessenberg, so Z_0^* A_{K-1}...A_0 Z_0 = h_ t_[K-2] ... t_[0]. A rotation of Z_k acts
// on the columns of factor k and the rows of factor k-1 (cyclically); every transformation
// below is such a pair, which is why the product is never needed.
class PeriodicQr {
 public:
  explicit PeriodicQr(const std::vector<Eigen::MatrixXd>& factors);
  ProductEigenvalues solve();

 private:
  void reduce(const std::vector<Eigen::MatrixXd>& factors);
  void restore(int i, Rotation g, int lo, int hi);
  bool negligible(int i) const;
  void sweep(int lo, int hi, int count_since_deflation);

  int n_;
  std::vector<MatrixXcd> t_;
  MatrixXcd h_;
  double h_norm_ = 0.0;
};

PeriodicQr::PeriodicQr(const std::vector<Eigen::MatrixXd>& factors)
    : n_(static_cast<int>(factors.front().rows())) {
  reduce(factors);
}

// Rows (i, i+1) of h_ have just been rotated by g, i.e. Z_0 by g^*. Passes the rotation through
// the triangular factors, each time removing the fill-in (i+1, i) with a row rotation that moves
// on to the next factor, and ends on the columns (i, i+1) of h_.
void PeriodicQr::restore(int i, Rotation g, int lo, int hi) {
  for (MatrixXcd& t : t_) {
    rotate_columns(t, i, g, lo, i + 1);
    g = annihilate(t(i, i), t(i + 1, i));
    rotate_rows(t, i, g, i, hi);
    t(i + 1, i) = 0.0;
  }
  rotate_columns(h_, i, g, lo, hi);
}

void PeriodicQr::reduce(const std::vector<Eigen::MatrixXd>& factors) {
  const int k_last = static_cast<int>(factors.size()) - 1;
  MatrixXcd z = MatrixXcd::Identity(n_, n_);
  for (int k = 0; k < k_last; ++k) {
    Eigen::HouseholderQR<MatrixXcd> qr(factors[k].cast<cd>() * z);
    t_.push_back(qr.matrixQR().triangularView<Eigen::Upper>());
    z = qr.householderQ();
  }
  h_ = factors[k_last].cast<cd>() * z;
  // Hessenberg form column by column. The rotation of rows (i-1, i) comes back, after the chase
  // through the triangular factors, as a rotation of columns (i-1, i) > j: no reduced column is
  // touched.
  for (int j = 0; j + 2 < n_; ++j) {
    for (int i = n_ - 1; i >= j + 2; --i) {
      const Rotation g = annihilate(h_(i - 1, j), h_(i, j));
      rotate_rows(h_, i - 1, g, j, n_ - 1);
      h_(i, j) = 0.0;
      restore(i - 1, g, 0, n_ - 1);
    }
  }
  h_norm_ = h_.norm();
}

// Subdiagonal entry (i, i-1) of h_ small against its neighbours on the diagonal: setting it to
// zero is a perturbation of h_ of relative size eps, like rounding.
bool PeriodicQr::negligible(int i) const {
  double scale = std::abs(h_(i - 1, i - 1)) + std::abs(h_(i, i));
  if (scale == 0.0) scale = h_norm_;
  return std::abs(h_(i, i - 1)) <= kEps * scale;
}

// One implicit single-shift QR sweep of the product on the unreduced window [lo, hi].
void PeriodicQr::sweep(int lo, int hi, int count_since_deflation) {
  // Trailing 2x2 block of the product: with triangular factors it is the trailing 2x2 block of
  // h_ times the product of the trailing 3x3 blocks (2x2 for a window of two).
  const int w = std::min(3, hi - lo + 1), r = hi - w + 1;
  double log_scale = 0.0;
  MatrixXcd p = MatrixXcd::Identity(w, w);
  for (const MatrixXcd& t : t_) {
    p = t.block(r, r, w, w).triangularView<Eigen::Upper>() * p;
    normalize(p, log_scale);
  }
  p = h_.block(r, r, w, w) * p;
  normalize(p, log_scale);
  const cd a = p(w - 2, w - 2), b = p(w - 2, w - 1), c = p(w - 1, w - 2), d = p(w - 1, w - 1);

  cd shift;
  if (count_since_deflation % 10 == 0) {
    // Exceptional shift: a pseudo-random point at the scale of the block breaks cycles.
    const double angle = 2.399963229728653 * count_since_deflation;  // golden angle
    shift = d + 0.5 * p.cwiseAbs().maxCoeff() * std::polar(1.0, angle);
  } else {
    // Wilkinson: the eigenvalue of the block closer to d, as d - bc / (larger root of
    // mu^2 - 2 q mu - bc), which avoids cancellation.
    const cd q = 0.5 * (a - d), root = std::sqrt(q * q + b * c);
    const cd den = std::abs(q + root) >= std::abs(q - root) ? q + root : q - root;
    shift = den == 0.0 ? d : d - b * c / den;
  }

  // First column of (product - shift) on the window: the triangular factors only scale e_lo, by
  // tau = prod t(lo, lo). Both terms are brought to a common scale before subtracting.
  ScaledComplex tau;
  for (const MatrixXcd& t : t_) tau.multiply(t(lo, lo));
  cd x0 = -shift, x1 = 0.0;
  if (tau.mantissa != 0.0) {
    const double log_tau = tau.exponent * std::numbers::ln2;
    const double common = std::max(log_tau, log_scale);
    const cd tau_scaled = tau.mantissa * std::exp(log_tau - common);
    x0 = h_(lo, lo) * tau_scaled - shift * std::exp(log_scale - common);
    x1 = h_(lo + 1, lo) * tau_scaled;
  }
  // Graded window: with h_(lo+1, lo) not negligible, |x1| < eps |x0| means the shift is far
  // above the top of the product. The shift is accurate to eps only, so a shifted sweep gains a
  // factor eps at best (and nothing once x1 underflows, or if a factor is singular there),
  // while a zero shift gains the ratio of the eigenvalues, then tiny. Any first rotation gives a
  // valid similarity.
  if (std::abs(x1) < kEps * std::abs(x0) || x1 == 0.0) {
    x0 = h_(lo, lo);
    x1 = h_(lo + 1, lo);
  }

  Rotation g = annihilate(x0, x1);
  rotate_rows(h_, lo, g, lo, hi);
  restore(lo, g, lo, hi);
  // Chase the bulge at (i+2, i) down the subdiagonal of h_.
  for (int i = lo; i + 2 <= hi; ++i) {
    g = annihilate(h_(i + 1, i), h_(i + 2, i));
    rotate_rows(h_, i + 1, g, i, hi);
    h_(i + 2, i) = 0.0;
    restore(i + 1, g, lo, hi);
  }
}

ProductEigenvalues PeriodicQr::solve() {
  ProductEigenvalues result;
  // Per eigenvalue, as LAPACK's zlahqr; convergence normally takes a few sweeps.
  const int max_sweeps = 30 * std::max(10, n_);
  int count = 0;  // sweeps since the last deflation
  for (int hi = n_ - 1; hi > 0;) {
    int lo = hi;
    while (lo > 0 && !negligible(lo)) --lo;
    if (lo > 0) h_(lo, lo - 1) = 0.0;
    if (lo == hi) {
      --hi;
      count = 0;
      continue;
    }
    if (count >= max_sweeps) {
      std::ostringstream message;
      message << "product_eigenvalues: periodic QR did not converge in " << max_sweeps
              << " sweeps (window " << lo << ".." << hi << ")";
      throw std::runtime_error(message.str());
    }
    ++count;
    ++result.iterations;
    sweep(lo, hi, count);
  }

  for (int i = 0; i < n_; ++i) {
    ScaledComplex lambda;
    lambda.multiply(h_(i, i));
    for (const MatrixXcd& t : t_) lambda.multiply(t(i, i));
    result.values.push_back(lambda.value());
    result.log_moduli.push_back(lambda.log_modulus());
  }
  return result;
}

}  // namespace

ProductEigenvalues product_eigenvalues(const std::vector<Eigen::MatrixXd>& factors) {
  if (factors.empty()) throw std::invalid_argument("product_eigenvalues: no factors");
  const Eigen::Index n = factors.front().rows();
  for (std::size_t k = 0; k < factors.size(); ++k) {
    const Eigen::MatrixXd& a = factors[k];
    if (a.rows() != n || a.cols() != n) {
      std::ostringstream message;
      message << "product_eigenvalues: factor " << k << " is " << a.rows() << " x " << a.cols()
              << ", expected " << n << " x " << n;
      throw std::invalid_argument(message.str());
    }
    if (!a.allFinite()) {
      std::ostringstream message;
      message << "product_eigenvalues: factor " << k << " has non-finite entries";
      throw std::invalid_argument(message.str());
    }
  }
  if (n == 0) return {};
  return PeriodicQr(factors).solve();
}

}  // namespace sympathy
