#include "sympathy/continuation/broyden.hpp"

#include <gtest/gtest.h>

namespace sympathy {
namespace {

// A nonlinear system with root x* = (1, 2, 3, 4): F_i = (x_i - i - 1) + 0.1 (x_(i+1) - i - 2)^2.
Eigen::VectorXd residual(const Eigen::VectorXd& x) {
  const int n = static_cast<int>(x.size());
  Eigen::VectorXd f(n);
  for (int i = 0; i < n; ++i) {
    const double next = i + 1 < n ? x[i + 1] - (i + 2) : 0.0;
    f[i] = (x[i] - (i + 1)) + 0.1 * next * next;
  }
  return f;
}

// Expected: the steps of Broyden's method with its matrices formed and updated explicitly,
// B+ = B + (y - B s) s^T W / (s^T W s), in the weighted inner product <u, v> = u^T W v. The
// matrix-free form must take the same steps (to rounding), and both converge superlinearly from
// a start 0.3 off with B_0 the Jacobian at the start perturbed by 20%.
TEST(Broyden, StepsMatchTheExplicitUpdatesAndConvergeSuperlinearly) {
  const int n = 4;
  const Eigen::VectorXd weights = (Eigen::VectorXd(n) << 1.0, 4.0, 0.25, 2.0).finished();
  auto dot = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    return (weights.array() * u.array() * v.array()).sum();
  };
  Eigen::VectorXd x0 = (Eigen::VectorXd(n) << 1.3, 1.7, 3.3, 3.8).finished();
  Eigen::MatrixXd b0 = Eigen::MatrixXd::Identity(n, n);
  for (int i = 0; i + 1 < n; ++i) b0(i, i + 1) = 0.2 * (x0[i + 1] - (i + 2));
  b0 *= 1.2;
  b0(2, 0) = 0.1;

  Eigen::VectorXd x = x0, xe = x0;
  Eigen::MatrixXd b = b0;
  std::vector<Eigen::VectorXd> steps;
  std::vector<double> norms;
  for (int k = 0; k < 20; ++k) {
    const Eigen::VectorXd f = residual(x);
    norms.push_back(f.cwiseAbs().maxCoeff());
    if (norms.back() < 1e-14) break;
    const auto s = broyden_step(Eigen::VectorXd(-b0.lu().solve(f)), steps, dot);
    ASSERT_TRUE(s.has_value());
    // The explicit method from the same point.
    const Eigen::VectorXd fe = residual(xe);
    const Eigen::VectorXd se = -b.lu().solve(fe);
    EXPECT_LT((*s - se).norm(), 1e-10 * (1.0 + se.norm())) << "step " << k;
    const Eigen::VectorXd y = residual(xe + se) - fe;
    b += (y - b * se) * (weights.asDiagonal() * se).transpose() / dot(se, se);
    xe += se;
    steps.push_back(*s);
    x += *s;
  }
  EXPECT_LT(norms.back(), 1e-12);
  // Faster than the chord method with B_0 (which converges linearly, here at about 0.25 a step),
  // and with the contraction improving as it goes: superlinear.
  Eigen::VectorXd xc = x0;
  int chord_steps = 0;
  while (residual(xc).cwiseAbs().maxCoeff() >= 1e-12 && chord_steps < 100) {
    xc -= b0.lu().solve(residual(xc));
    ++chord_steps;
  }
  const int broyden_steps = static_cast<int>(norms.size()) - 1;
  EXPECT_LT(broyden_steps + 5, chord_steps);
  const std::size_t last = norms.size() - 1;
  EXPECT_LT(norms[last] / norms[last - 1], 0.1 * norms[1] / norms[0]);
}

TEST(Broyden, RefusesANearlySingularUpdate) {
  auto dot = [](const Eigen::VectorXd& u, const Eigen::VectorXd& v) { return u.dot(v); };
  const std::vector<Eigen::VectorXd> steps{Eigen::Vector2d(1.0, 0.0)};
  // z along the last step with <s, z> / <s, s> = 0.95: the denominator 0.05 is refused.
  EXPECT_FALSE(broyden_step(Eigen::Vector2d(0.95, 0.0), steps, dot).has_value());
  EXPECT_TRUE(broyden_step(Eigen::Vector2d(0.5, 0.3), steps, dot).has_value());
}

}  // namespace
}  // namespace sympathy
