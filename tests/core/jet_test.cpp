// Taylor jets (core/jet.hpp) against an independent reference: g(x0 + s v)'s coefficients by the
// Cauchy integral of g's complex extension (std::complex's functions) on a circle of radius 0.1,
// 64 points: aliasing 0.1^64, rounding about 1e-16 / 0.1^5 = 1e-11 at the fifth order.
#include "sympathy/core/jet.hpp"

#include <cmath>
#include <complex>
#include <functional>
#include <numbers>

#include <gtest/gtest.h>

#include "sympathy/core/autodiff_system.hpp"

namespace sympathy {
namespace {

using Complex = std::complex<double>;
using J = Jet<5>;
constexpr double kTolerance = 1e-9;  // relative to the largest coefficient

// The Taylor coefficients of g(x0 + s v) in s, from g on the complex circle x0 + 0.1 e^{i theta}.
std::array<Complex, 6> cauchy(const std::function<Complex(Complex)>& g, double x0, Complex v) {
  constexpr int M = 64;
  constexpr double r = 0.1;
  std::array<Complex, 6> c{};
  for (int m = 0; m < M; ++m) {
    const Complex w = std::polar(1.0, 2 * std::numbers::pi * m / M);
    const Complex value = g(x0 + r * w);
    for (int k = 0; k <= 5; ++k) c[k] += value * std::pow(w, -k) / (M * std::pow(r, k));
  }
  for (int k = 0; k <= 5; ++k) c[k] *= std::pow(v, k);
  return c;
}

J seeded(double x0, Complex v) {
  J a(x0);
  a.c[1] = v;
  return a;
}

void expect_coefficients(const J& jet, const std::array<Complex, 6>& reference, const char* what) {
  double size = 0.0;
  for (const auto& c : reference) size = std::max(size, std::abs(c));
  for (int k = 0; k <= 5; ++k)
    EXPECT_LT(std::abs(jet.c[k] - reference[k]), kTolerance * size)
        << what << ", order " << k << ": " << jet.c[k] << " vs " << reference[k];
}

TEST(Jet, ElementaryFunctionsMatchTheCauchyIntegral) {
  const Complex v(0.7, -0.4);
  const double x0 = 0.3;  // inside every function's domain (asin, acos, log, sqrt)
  const J a = seeded(x0, v);
  expect_coefficients(sin(a), cauchy([](Complex z) { return std::sin(z); }, x0, v), "sin");
  expect_coefficients(cos(a), cauchy([](Complex z) { return std::cos(z); }, x0, v), "cos");
  expect_coefficients(tan(a), cauchy([](Complex z) { return std::tan(z); }, x0, v), "tan");
  expect_coefficients(exp(a), cauchy([](Complex z) { return std::exp(z); }, x0, v), "exp");
  expect_coefficients(log(a), cauchy([](Complex z) { return std::log(z); }, x0, v), "log");
  expect_coefficients(sqrt(a), cauchy([](Complex z) { return std::sqrt(z); }, x0, v), "sqrt");
  expect_coefficients(tanh(a), cauchy([](Complex z) { return std::tanh(z); }, x0, v), "tanh");
  expect_coefficients(atan(a), cauchy([](Complex z) { return std::atan(z); }, x0, v), "atan");
  expect_coefficients(asin(a), cauchy([](Complex z) { return std::asin(z); }, x0, v), "asin");
  expect_coefficients(acos(a), cauchy([](Complex z) { return std::acos(z); }, x0, v), "acos");
  expect_coefficients(sinh(a), cauchy([](Complex z) { return std::sinh(z); }, x0, v), "sinh");
  expect_coefficients(cosh(a), cauchy([](Complex z) { return std::cosh(z); }, x0, v), "cosh");
  expect_coefficients(pow(a, 2.5), cauchy([](Complex z) { return std::pow(z, 2.5); }, x0, v),
                      "pow(a, 2.5)");
  expect_coefficients(pow(a, J(-3.0)), cauchy([](Complex z) { return std::pow(z, -3.0); }, x0, v),
                      "pow(a, -3)");
  expect_coefficients(pow(a, a), cauchy([](Complex z) { return std::pow(z, z); }, x0, v),
                      "pow(a, a)");
  expect_coefficients(pow(2.0, a), cauchy([](Complex z) { return std::pow(2.0, z); }, x0, v),
                      "pow(2, a)");
  // Arithmetic together: a quotient of compositions.
  expect_coefficients(
      exp(sin(a)) / (1.0 + a * a) - 3.0 * a,
      cauchy([](Complex z) { return std::exp(std::sin(z)) / (1.0 + z * z) - 3.0 * z; }, x0, v),
      "exp(sin a) / (1 + a^2) - 3a");
  // atan2(y, x) = atan(y / x) where x > 0.
  const J y = seeded(0.4, Complex(0.2, 0.5)), x = 1.3 + 0.5 * a;
  const J direct = atan2(y, x), quotient = atan(y / x);
  for (int k = 0; k <= 5; ++k) EXPECT_LT(std::abs(direct.c[k] - quotient.c[k]), 1e-13) << k;
}

// erf's derivatives are Hermite polynomials times its slope: erf^(k+1)(x) = (-1)^k H_k(x) 2 /
// sqrt(pi) e^(-x^2), H_0..H_4 = 1, 2x, 4x^2 - 2, 8x^3 - 12x, 16x^4 - 48x^2 + 12.
TEST(Jet, ErfFollowsHermitePolynomials) {
  const double x = 0.6;
  const Complex v(0.5, 0.8);
  const J e = erf(seeded(x, v));
  const double slope = 2 / std::sqrt(std::numbers::pi) * std::exp(-x * x);
  const double hermite[5] = {1, 2 * x, 4 * x * x - 2, 8 * x * x * x - 12 * x,
                             16 * std::pow(x, 4) - 48 * x * x + 12};
  EXPECT_NEAR(e.c[0].real(), std::erf(x), 1e-15);
  double factorial = 1.0;
  for (int k = 1; k <= 5; ++k) {
    factorial *= k;
    const Complex expected =
        (k % 2 ? 1.0 : -1.0) * hermite[k - 1] * slope * std::pow(v, k) / factorial;
    EXPECT_LT(std::abs(e.c[k] - expected), 1e-14) << k;
  }
}

// Whole powers by products are exact where the base is 0, and abs takes the upper branch there.
TEST(Jet, WholePowersAtZeroAndAbs) {
  const J a = seeded(0.0, Complex(1.0, 1.0));
  const J cube = pow(a, 3.0);
  EXPECT_EQ(cube.c[3], std::pow(Complex(1.0, 1.0), 3));
  EXPECT_EQ(cube.c[2], Complex(0.0));
  EXPECT_EQ(abs(a).c[1], a.c[1]);
  EXPECT_EQ(abs(seeded(-2.0, 1.0)).c[1], Complex(-1.0));
  EXPECT_EQ(value_of(seeded(-2.0, 1.0)), -2.0);
}

// A templated system's Taylor coefficients: the first is J v (the same evaluate on dual numbers),
// the second the quadratic form of a polynomial, exactly.
class Quadratic final : public AutoDiffSystem<Quadratic> {
 public:
  Quadratic() { set_parameter_layout({{"a", {0}}}, {2.0}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double /*t*/, const T* z, const P* p, T* dz) const {
    using std::sin;
    dz[0] = p[0] * z[0] * z[1] + sin(z[1]);
    dz[1] = z[0] * z[0] * z[0] - z[1];
  }
};

TEST(Jet, SystemsGiveTheirTaylorCoefficients) {
  const Quadratic system;
  const Eigen::VectorXd x = Eigen::Vector2d(0.4, -1.1);
  const Eigen::VectorXd p = system.default_parameters();
  const Eigen::VectorXcd v = Eigen::Vector2cd(Complex(0.3, 0.2), Complex(-0.6, 0.9));
  std::vector<Complex> out(2 * 6);
  ASSERT_TRUE(system.taylor_coefficients(0.0, x.data(), p.data(), v.data(), 5, out.data()));
  Eigen::MatrixXd jac;
  system.jacobian(0.0, x.data(), p.data(), jac);
  const Eigen::VectorXcd jv = jac.cast<Complex>() * v;
  for (int i = 0; i < 2; ++i) EXPECT_LT(std::abs(out[2 + i] - jv[i]), 1e-15);
  // Second order: (a v0 v1 - sin(x1) v1^2 / 2, 3 x0 v0^2).
  EXPECT_LT(std::abs(out[4] - (2.0 * v[0] * v[1] - std::sin(x[1]) * v[1] * v[1] / 2.0)), 1e-15);
  EXPECT_LT(std::abs(out[5] - 3.0 * x[0] * v[0] * v[0]), 1e-15);
  // Fifth order: only sin's, cos(x1) v1^5 / 120.
  EXPECT_LT(std::abs(out[10] - std::cos(x[1]) * std::pow(v[1], 5) / 120.0), 1e-15);
  EXPECT_EQ(out[11], Complex(0.0));
}

}  // namespace
}  // namespace sympathy
