#include "sympathy/floquet/periodic_schur.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

namespace sympathy {
namespace {

using cd = std::complex<double>;

Eigen::MatrixXd gaussian(int n, std::mt19937& rng) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) a(i, j) = normal(rng);
  return a;
}

// Q (I + 0.3 G / sqrt(n)) with Q random orthogonal: singular values within [0.3, 1.7] or so,
// so the factors and the similarities built from them are well conditioned.
Eigen::MatrixXd well_conditioned(int n, std::mt19937& rng) {
  const Eigen::MatrixXd q = Eigen::HouseholderQR<Eigen::MatrixXd>(gaussian(n, rng)).householderQ();
  return q * (Eigen::MatrixXd::Identity(n, n) + 0.3 / std::sqrt(n) * gaussian(n, rng));
}

// A[K-1] * ... * A[0], formed: only for comparison.
Eigen::MatrixXd formed_product(const std::vector<Eigen::MatrixXd>& factors) {
  Eigen::MatrixXd p = factors.front();
  for (std::size_t k = 1; k < factors.size(); ++k) p = factors[k] * p;
  return p;
}

std::vector<cd> eigen_solver_values(const Eigen::MatrixXd& a) {
  const Eigen::VectorXcd v = Eigen::EigenSolver<Eigen::MatrixXd>(a, false).eigenvalues();
  return {v.data(), v.data() + v.size()};
}

double spectral_radius(const std::vector<cd>& values) {
  double r = 0.0;
  for (const cd& v : values) r = std::max(r, std::abs(v));
  return r;
}

// Distance between two multisets of equal size: each expected value is matched to the nearest
// unused computed one, and the largest distance is returned (infinite if sizes differ).
double mismatch(const std::vector<cd>& computed, const std::vector<cd>& expected) {
  if (computed.size() != expected.size()) return std::numeric_limits<double>::infinity();
  std::vector<bool> used(computed.size(), false);
  double worst = 0.0;
  for (const cd& e : expected) {
    std::size_t best = 0;
    double best_distance = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < computed.size(); ++i) {
      if (!used[i] && std::abs(computed[i] - e) < best_distance) {
        best = i;
        best_distance = std::abs(computed[i] - e);
      }
    }
    used[best] = true;
    worst = std::max(worst, best_distance);
  }
  return worst;
}

std::vector<double> sorted(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v;
}

// log_moduli agrees with the values wherever these are representable.
void expect_consistent(const ProductEigenvalues& r) {
  ASSERT_EQ(r.values.size(), r.log_moduli.size());
  for (std::size_t i = 0; i < r.values.size(); ++i) {
    const double m = std::abs(r.values[i]);
    if (m > 0.0 && std::isfinite(m)) {
      EXPECT_NEAR(std::log(m), r.log_moduli[i], 1e-13);
    }
  }
}

// Factors A_k = S_{k+1} D_k S_k^{-1} with S_K = S_0: the product is S_0 (prod D_k) S_0^{-1},
// whose spectrum is known exactly, while the factors themselves are full.
std::vector<Eigen::MatrixXd> similar_factors(const std::vector<Eigen::MatrixXd>& blocks,
                                             std::mt19937& rng) {
  const int n = static_cast<int>(blocks.front().rows());
  const std::size_t K = blocks.size();
  std::vector<Eigen::MatrixXd> s;
  for (std::size_t k = 0; k < K; ++k) s.push_back(well_conditioned(n, rng));
  s.push_back(s.front());
  std::vector<Eigen::MatrixXd> factors;
  for (std::size_t k = 0; k < K; ++k) factors.push_back(s[k + 1] * blocks[k] * s[k].inverse());
  return factors;
}

// With one factor the method is ordinary Hessenberg QR: expected values from Eigen's real
// Schur-based EigenSolver, both backward stable, so they agree to a few eps times the scale.
TEST(PeriodicSchur, SingleFactorMatchesEigenSolver) {
  std::mt19937 rng(1);
  for (int n : {1, 2, 5, 12}) {
    const Eigen::MatrixXd a = gaussian(n, rng);
    const ProductEigenvalues r = product_eigenvalues({a});
    const std::vector<cd> expected = eigen_solver_values(a);
    EXPECT_LE(mismatch(r.values, expected), 1e-12 * spectral_radius(expected)) << "n = " << n;
    expect_consistent(r);
  }
}

// Random well-conditioned factors scaled to determinant +-1, so the product is O(1) and its
// eigenvalues spread over a few orders of magnitude at most: the formed product is then an
// accurate reference, to eps times K times eigenvalue condition numbers.
TEST(PeriodicSchur, RandomProductsMatchFormedProduct) {
  std::mt19937 rng(2);
  for (int K : {3, 10, 50}) {
    for (int n : {2, 6, 12}) {
      std::vector<Eigen::MatrixXd> factors;
      for (int k = 0; k < K; ++k) {
        Eigen::MatrixXd a = well_conditioned(n, rng);
        a /= std::pow(std::abs(a.determinant()), 1.0 / n);
        factors.push_back(a);
      }
      const ProductEigenvalues r = product_eigenvalues(factors);
      const std::vector<cd> expected = eigen_solver_values(formed_product(factors));
      EXPECT_LE(mismatch(r.values, expected), 1e-10 * spectral_radius(expected))
          << "K = " << K << ", n = " << n;
      // det(product) = prod det(A_k) = +-1, without forming anything.
      double log_det = 0.0;
      for (double l : r.log_moduli) log_det += l;
      EXPECT_NEAR(log_det, 0.0, 1e-10) << "K = " << K << ", n = " << n;
      expect_consistent(r);
    }
  }
}

// 50 factors with eigenvalue factors 2 and 1/2 alternating (product 1), exp(-3 +- 0.5)
// alternating (exp(-150)), 1/2 (2^-50) and exp(0.1) (exp(5)), hidden by full similarities.
// The expected log moduli are exact. The formed product cannot see exp(-150) (nor 2^-50): its
// rounding errors are of order eps * exp(5), 1e-15 to 1e-14.
TEST(PeriodicSchur, KnownSpectrumBeyondTheFormedProduct) {
  std::mt19937 rng(3);
  const int K = 50;
  std::vector<Eigen::MatrixXd> blocks;
  for (int k = 0; k < K; ++k) {
    const double sign = k % 2 == 0 ? 1.0 : -1.0;
    blocks.push_back(
        Eigen::Vector4d(std::pow(2.0, sign), std::exp(-3.0 + 0.5 * sign), 0.5, std::exp(0.1))
            .asDiagonal());
  }
  const std::vector<Eigen::MatrixXd> factors = similar_factors(blocks, rng);
  const ProductEigenvalues r = product_eigenvalues(factors);
  const std::vector<double> expected{-150.0, -50.0 * std::numbers::ln2, 0.0, 5.0};
  const std::vector<double> logs = sorted(r.log_moduli);
  ASSERT_EQ(logs.size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(logs[i], expected[i], 1e-9) << "eigenvalue " << i;
  // All eigenvalues are positive reals.
  for (const cd& v : r.values) {
    EXPECT_GT(v.real(), 0.0);
    EXPECT_LE(std::abs(v.imag()), 1e-12 * std::abs(v));
  }
  expect_consistent(r);

  // The formed product's smallest eigenvalue is rounding noise, off by tens of orders of
  // magnitude.
  double smallest = std::numeric_limits<double>::infinity();
  for (const cd& v : eigen_solver_values(formed_product(factors)))
    smallest = std::min(smallest, std::abs(v));
  EXPECT_GT(std::log(smallest), -150.0 + 50.0);
}

// 400 factors: eigenvalues exp(-1200) and exp(800) under- and overflow double, -1 does not.
// Expected log moduli exact by construction; values 0, +infinity and -1.
TEST(PeriodicSchur, LogModuliBeyondTheRangeOfDouble) {
  std::mt19937 rng(4);
  const int K = 400;
  std::vector<Eigen::MatrixXd> blocks;
  for (int k = 0; k < K; ++k)
    blocks.push_back(
        Eigen::Vector3d(std::exp(-3.0), std::exp(2.0), k == 7 ? -1.0 : 1.0).asDiagonal());
  const ProductEigenvalues r = product_eigenvalues(similar_factors(blocks, rng));
  const std::vector<double> logs = sorted(r.log_moduli);
  ASSERT_EQ(logs.size(), 3u);
  EXPECT_NEAR(logs[0], -1200.0, 1e-9);
  EXPECT_NEAR(logs[1], 0.0, 1e-9);
  EXPECT_NEAR(logs[2], 800.0, 1e-9);
  for (std::size_t i = 0; i < 3; ++i) {
    const double l = r.log_moduli[i];
    const cd v = r.values[i];
    if (l < -1000.0) {
      EXPECT_EQ(v, cd(0.0, 0.0));
    } else if (l > 700.0) {
      EXPECT_TRUE(std::isinf(v.real()) && v.real() > 0.0);
    } else {
      EXPECT_LE(std::abs(v - cd(-1.0, 0.0)), 1e-12);
    }
  }
}

// 1000 factors exp(-3), 1, exp(2) behind near-identity similarities, so the reduced product is
// graded with the tiny eigenvalue on top. Shifted sweeps gain only a factor eps each there
// (about 90 sweeps for exp(-3000), and none once the first rotation underflows); zero-shift
// sweeps deflate at once. Expected log moduli exact by construction.
TEST(PeriodicSchur, StronglyGradedProductConvergesQuickly) {
  std::mt19937 rng(7);
  const int K = 1000;
  std::vector<Eigen::MatrixXd> s, factors;
  for (int k = 0; k < K; ++k)
    s.push_back(Eigen::MatrixXd::Identity(3, 3) + 0.05 * gaussian(3, rng));
  s.push_back(s.front());
  const Eigen::MatrixXd d = Eigen::Vector3d(std::exp(-3.0), 1.0, std::exp(2.0)).asDiagonal();
  for (int k = 0; k < K; ++k) factors.push_back(s[k + 1] * d * s[k].inverse());
  const ProductEigenvalues r = product_eigenvalues(factors);
  const std::vector<double> logs = sorted(r.log_moduli);
  ASSERT_EQ(logs.size(), 3u);
  EXPECT_NEAR(logs[0], -3000.0, 1e-9);
  EXPECT_NEAR(logs[1], 0.0, 1e-9);
  EXPECT_NEAR(logs[2], 2000.0, 1e-9);
  EXPECT_LE(r.iterations, 6);
}

// Rotation-scalings r_k R(phi_k) behind full similarities: the product is similar to
// (prod r_k) R(sum phi_k), eigenvalues (prod r_k) exp(+-i sum phi_k), exact by construction.
// With n = 3 a real eigenvalue (product 1.1^K) shares the spectrum.
TEST(PeriodicSchur, ComplexPairFromRotationScalings) {
  std::mt19937 rng(5);
  for (int K : {1, 7, 40}) {
    for (int n : {2, 3}) {
      std::vector<Eigen::MatrixXd> blocks;
      double modulus = 1.0, angle = 0.0;
      for (int k = 0; k < K; ++k) {
        const double rk = 0.9 + 0.02 * (k % 5), phi = 0.3 + 0.1 * k;
        modulus *= rk;
        angle += phi;
        Eigen::MatrixXd b = Eigen::MatrixXd::Identity(n, n) * 1.1;
        b.topLeftCorner(2, 2) << rk * std::cos(phi), -rk * std::sin(phi), rk * std::sin(phi),
            rk * std::cos(phi);
        blocks.push_back(b);
      }
      std::vector<cd> expected{std::polar(modulus, angle), std::polar(modulus, -angle)};
      if (n == 3) expected.push_back(std::pow(1.1, K));
      const ProductEigenvalues r = product_eigenvalues(similar_factors(blocks, rng));
      EXPECT_LE(mismatch(r.values, expected), 1e-12 * spectral_radius(expected))
          << "K = " << K << ", n = " << n;
      expect_consistent(r);
    }
  }
}

// The cyclic shift of 5 entries, and its cube as three factors: the classic case where
// Wilkinson shifts alone never converge (for K = 1 every shift is 0 and a sweep gives back the
// same matrix), so this checks the exceptional shifts. Expected: the fifth roots of unity,
// exactly (the cube of a 5-cycle is a 5-cycle).
TEST(PeriodicSchur, CyclicPermutationNeedsExceptionalShifts) {
  const int n = 5;
  Eigen::MatrixXd p = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) p((i + 1) % n, i) = 1.0;
  std::vector<cd> expected;
  for (int k = 0; k < n; ++k) expected.push_back(std::polar(1.0, 2.0 * std::numbers::pi * k / n));
  for (int K : {1, 3}) {
    const ProductEigenvalues r = product_eigenvalues(std::vector<Eigen::MatrixXd>(K, p));
    EXPECT_LE(mismatch(r.values, expected), 1e-12) << "K = " << K;
    EXPECT_GE(r.iterations, 10) << "K = " << K;  // it did need an exceptional shift
  }
}

// Factors already upper triangular: the eigenvalues are the products of the diagonal entries,
// computed here directly (K = 20 products of O(1) numbers, exact to a few eps).
TEST(PeriodicSchur, TriangularFactorsGiveDiagonalProducts) {
  std::mt19937 rng(6);
  const int n = 5, K = 20;
  std::vector<Eigen::MatrixXd> factors;
  Eigen::VectorXd diagonal = Eigen::VectorXd::Ones(n);
  for (int k = 0; k < K; ++k) {
    Eigen::MatrixXd a = gaussian(n, rng).triangularView<Eigen::Upper>();
    for (int i = 0; i < n; ++i) a(i, i) = (1.0 + 0.1 * i) * (k % 3 == 0 ? -1.0 : 1.0);
    diagonal = diagonal.cwiseProduct(a.diagonal());
    factors.push_back(a);
  }
  const ProductEigenvalues r = product_eigenvalues(factors);
  std::vector<cd> expected(diagonal.data(), diagonal.data() + n);
  EXPECT_LE(mismatch(r.values, expected), 1e-13 * spectral_radius(expected));
}

TEST(PeriodicSchur, RejectsBadInput) {
  EXPECT_THROW(product_eigenvalues({}), std::invalid_argument);
  EXPECT_THROW(product_eigenvalues({Eigen::MatrixXd::Ones(2, 3)}), std::invalid_argument);
  EXPECT_THROW(product_eigenvalues({Eigen::MatrixXd::Identity(2, 2), Eigen::MatrixXd::Ones(3, 3)}),
               std::invalid_argument);
  Eigen::MatrixXd bad = Eigen::MatrixXd::Identity(2, 2);
  bad(1, 0) = std::nan("");
  EXPECT_THROW(product_eigenvalues({Eigen::MatrixXd::Identity(2, 2), bad}), std::invalid_argument);
  // Zero-sized factors are consistent: no eigenvalues.
  EXPECT_TRUE(product_eigenvalues({Eigen::MatrixXd(0, 0)}).values.empty());
}

}  // namespace
}  // namespace sympathy
