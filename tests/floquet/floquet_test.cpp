#include "sympathy/floquet/floquet.hpp"

#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "../../floquet/summary.hpp"

namespace sympathy {
namespace {

// A monodromy with known eigenvalues and eigenvectors: M = V diag(mu) V^-1.
Eigen::MatrixXd with_spectrum(const Eigen::VectorXd& mu, const Eigen::MatrixXd& v) {
  return v * mu.asDiagonal() * v.inverse();
}

Eigen::MatrixXd random_basis(int n, unsigned seed) {
  std::srand(seed);
  return Eigen::MatrixXd::Random(n, n) + 2.0 * Eigen::MatrixXd::Identity(n, n);
}

// The trivial multiplier is the one whose eigenvector is f, even when another multiplier is
// nearer to 1 (as near a branch point): here mu = 1 + 2e-7 along f, and 1 + 1e-9 elsewhere.
TEST(Floquet, TrivialMultiplierFoundByEigenvectorNotByDistance) {
  const Eigen::MatrixXd v = random_basis(4, 3);
  Eigen::VectorXd mu(4);
  mu << 0.5, 1.0 + 1e-9, 1.0 + 2e-7, 0.9;
  const auto a = analyze_floquet({with_spectrum(mu, v)}, v.col(2));
  ASSERT_GE(a.trivial, 0);
  EXPECT_NEAR(a.multipliers[a.trivial].value.real(), 1.0 + 2e-7, 1e-12);
  EXPECT_NEAR(a.trivial_error, 2e-7, 1e-12);
  EXPECT_GT(a.trivial_alignment, 1.0 - 1e-9);
  // Sorted by modulus; the remaining largest is the one at 1 + 1e-9: marginal at tolerance 1e-6.
  EXPECT_NEAR(a.max_modulus, 1.0 + 1e-9, 1e-12);
  EXPECT_EQ(a.stability, Stability::Marginal);
  for (std::size_t i = 1; i < a.multipliers.size(); ++i)
    EXPECT_GE(a.multipliers[i - 1].modulus(), a.multipliers[i].modulus());
}

// Classification against the stated tolerance (default 1e-6).
TEST(Floquet, StabilityVerdicts) {
  const Eigen::MatrixXd v = random_basis(3, 5);
  auto verdict = [&](double largest) {
    Eigen::VectorXd mu(3);
    mu << 1.0, largest, 0.3;
    return analyze_floquet({with_spectrum(mu, v)}, v.col(0));
  };
  EXPECT_EQ(verdict(0.97).stability, Stability::Stable);
  EXPECT_EQ(verdict(1.0 - 2e-6).stability, Stability::Stable);
  EXPECT_EQ(verdict(1.0 + 5e-7).stability, Stability::Marginal);
  const auto u = verdict(1.13);
  EXPECT_EQ(u.stability, Stability::Unstable);
  EXPECT_EQ(u.unstable_count, 1);
  EXPECT_NEAR(u.max_modulus, 1.13, 1e-12);
}

// A verdict holds within the multipliers' error, measured by the trivial one's: with the trivial
// multiplier at 1 + 1e-3 (an orbit resolved no better than that), 1.0005 and 0.9995 are within the
// error of the circle (unresolved, not "unstable" or "stable"), 1.01 and 0.98 are not; at 1 + 1e-9
// the same 1.0005 is unstable.
TEST(Floquet, VerdictsHoldWithinTheTrivialMultipliersError) {
  const Eigen::MatrixXd v = random_basis(3, 5);
  auto verdict = [&](double trivial, double largest) {
    Eigen::VectorXd mu(3);
    mu << trivial, largest, 0.3;
    return analyze_floquet({with_spectrum(mu, v)}, v.col(0)).stability;
  };
  EXPECT_EQ(verdict(1.0 + 1e-3, 1.0005), Stability::Unresolved);
  EXPECT_EQ(verdict(1.0 + 1e-3, 0.9995), Stability::Unresolved);
  EXPECT_EQ(verdict(1.0 + 1e-3, 1.01), Stability::Unstable);
  EXPECT_EQ(verdict(1.0 + 1e-3, 0.98), Stability::Stable);
  EXPECT_EQ(verdict(1.0 + 1e-9, 1.0005), Stability::Unstable);
  EXPECT_EQ(verdict(1.0 + 1e-9, 1.0 + 5e-7), Stability::Marginal);
  EXPECT_EQ(to_string(Stability::Unresolved), "unresolved");
}

// A trivial multiplier out of the range of double (near a homoclinic orbit its value came out
// NaN: an overflowing modulus times a phase) resolves nothing: its error is infinite and the
// verdict unresolved. NaN compared as a small error had made AUTO's ab orbits at T 325 "stable"
// with a largest other multiplier of 0.
TEST(Floquet, ATrivialMultiplierOutOfRangeResolvesNothing) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const std::complex<double> value :
       {std::complex<double>(nan, nan), std::complex<double>(nan, 0.0),
        std::complex<double>(HUGE_VAL, 0.0)}) {
    FloquetAnalysis a;
    a.multipliers = {{value, 800.0, true}, {{0.5, 0.0}, std::log(0.5)}};
    summarize(a, FloquetOptions{});
    EXPECT_EQ(a.trivial, 0);
    EXPECT_TRUE(std::isinf(a.trivial_error));
    EXPECT_EQ(a.stability, Stability::Unresolved);
  }
  // The same with a trivial multiplier at 1 + 1e-9: stable, its error 1e-9.
  FloquetAnalysis a;
  a.multipliers = {{{1.0 + 1e-9, 0.0}, 1e-9, true}, {{0.5, 0.0}, std::log(0.5)}};
  summarize(a, FloquetOptions{});
  EXPECT_NEAR(a.trivial_error, 1e-9, 1e-15);
  EXPECT_EQ(a.stability, Stability::Stable);
}

// A family's structural multiplier (eigenvector along the family's direction) is marked and
// left out of the verdict, found by its eigenvector even when another multiplier, crossing 1
// near a branch point, is nearer to 1 than it.
TEST(Floquet, StructuralMultipliersFoundByEigenvector) {
  const Eigen::MatrixXd v = random_basis(5, 9);
  Eigen::VectorXd mu(5);
  mu << 1.0, 1.0 + 3e-9, 1.0 + 1e-10, 0.8, 0.95;  // trivial, structural, crossing, others
  // The direction as a null vector delivers it: mixed with f.
  const Eigen::VectorXd family = v.col(1) + 0.7 * v.col(0);
  const auto a = analyze_floquet({with_spectrum(mu, v)}, v.col(0), family);
  EXPECT_EQ(a.structural, 1);
  for (const auto& m : a.multipliers) {
    if (m.structural) {
      EXPECT_NEAR(m.value.real(), 1.0 + 3e-9, 1e-13);
    }
  }
  EXPECT_NEAR(a.max_modulus, 1.0 + 1e-10, 1e-13);  // the crossing one counts
  EXPECT_EQ(a.stability, Stability::Marginal);
  mu[2] = 0.9;
  const auto b = analyze_floquet({with_spectrum(mu, v)}, v.col(0), family);
  EXPECT_EQ(b.stability, Stability::Stable);
  EXPECT_NEAR(b.max_modulus, 0.95, 1e-12);
}

// Complex pairs keep their arguments; without f (a forced system) there is no trivial one.
TEST(Floquet, ComplexPairsAndForcedSystems) {
  Eigen::MatrixXd m(2, 2);
  const double r = 0.9, phi = 0.4;
  m << r * std::cos(phi), -r * std::sin(phi), r * std::sin(phi), r * std::cos(phi);
  const auto a = analyze_floquet({m}, Eigen::VectorXd());
  EXPECT_EQ(a.trivial, -1);
  ASSERT_EQ(a.multipliers.size(), 2u);
  EXPECT_NEAR(a.multipliers[0].modulus(), r, 1e-14);
  EXPECT_NEAR(std::abs(std::arg(a.multipliers[0].value)), phi, 1e-14);
  EXPECT_NEAR(a.multipliers[0].log_modulus, std::log(r), 1e-14);
  EXPECT_EQ(a.stability, Stability::Stable);
}

// At a branch point on a family of orbits three multipliers meet at 1: the trivial one, the
// family's (here coupled to f as when moving along the family shifts the phase: M v1 = v1 +
// 0.3 f, a Jordan block, whose eigenvalues the whole matrix gives only to ~sqrt(eps)), and the
// one crossing. The crossing one comes from the quotient by f and the family: its value to
// 1e-12 and the sign of |mu| - 1 right down to 1e-9 from 1, for one segment and for five
// (whose product is M). Exact values by construction.
TEST(Floquet, CrossingMultiplierAmongTheTrivialAndAFamilysOne) {
  const Eigen::MatrixXd v = random_basis(5, 11);
  for (double delta : {1e-5, 1e-7, 1e-9, -1e-9, -1e-7}) {
    Eigen::MatrixXd core = Eigen::VectorXd::Constant(5, 1.0).asDiagonal();
    core(2, 2) = 1.0 + delta;  // crossing
    core(3, 3) = 0.8;
    core(4, 4) = 0.95;
    core(0, 1) = 0.3;  // M v1 = v1 + 0.3 v0
    const Eigen::MatrixXd m = v * core * v.inverse();
    // Five factors whose product is m: m^(1/5) is awkward, so m = A5 ... A1 with A_k = I for k
    // < 5 except one random invertible pair that cancels.
    const Eigen::MatrixXd r = random_basis(5, 12);
    const std::vector<Eigen::MatrixXd> five{r, Eigen::MatrixXd::Identity(5, 5),
                                            Eigen::MatrixXd::Identity(5, 5), r.inverse(), m};
    for (const auto& segments : {std::vector<Eigen::MatrixXd>{m}, five}) {
      const auto a = analyze_floquet(segments, v.col(0), v.col(1));
      EXPECT_EQ(a.structural, 1);
      int others = 0;
      for (const auto& mu : a.multipliers) {
        if (mu.trivial || mu.structural) continue;
        ++others;
        if (std::abs(mu.value - 1.0) < 1e-3) {
          EXPECT_NEAR(mu.value.real(), 1.0 + delta, 1e-12) << delta;
          EXPECT_EQ(mu.modulus() > 1.0, delta > 0.0) << delta;
        }
      }
      EXPECT_EQ(others, 3);
      EXPECT_NEAR(a.max_modulus, std::max(1.0 + delta, 0.95), 1e-12) << delta;
    }
  }
}

// A family's multiplier and the trivial one form a Jordan block at 1 (M v1 = v1 + 0.3 f): an
// error of 1e-14 in the monodromy splits its eigenvalues by about sqrt(1e-14 * 0.3 * |V|) ~ 1e-7,
// but their values from the compression onto span(f, v1) move by O(1e-14) only. Expected values
// exact by construction; the split is checked too, so that the test cannot pass vacuously.
TEST(Floquet, TrivialAndFamilyMultipliersFirstOrderAccurateInAJordanBlock) {
  const Eigen::MatrixXd v = random_basis(5, 13);
  Eigen::MatrixXd core = Eigen::MatrixXd::Identity(5, 5);
  core(0, 1) = 0.3;
  core(3, 3) = 0.8;
  core(4, 4) = 0.95;
  core(2, 2) = 0.5;
  std::srand(14);
  const Eigen::MatrixXd m = v * core * v.inverse() + 1e-14 * Eigen::MatrixXd::Random(5, 5);
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(m);
  double split = 0.0;
  for (int i = 0; i < 5; ++i)
    if (std::abs(eig.eigenvalues()[i] - 1.0) < 1e-3)
      split = std::max(split, std::abs(eig.eigenvalues()[i] - 1.0));
  EXPECT_GT(split, 1e-9);  // the eigenvalues are this far off
  const auto a = analyze_floquet({m}, v.col(0), v.col(1));
  EXPECT_EQ(a.structural, 1);
  EXPECT_LT(a.trivial_error, 1e-12);
  for (const auto& mu : a.multipliers) {
    if (mu.structural) {
      EXPECT_NEAR(std::abs(mu.value - 1.0), 0.0, 1e-12);
    }
  }
  EXPECT_NEAR(a.max_modulus, 0.95, 1e-12);
}

}  // namespace
}  // namespace sympathy
