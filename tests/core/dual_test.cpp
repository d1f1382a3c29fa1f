#include "sympathy/core/dual.hpp"

#include <gtest/gtest.h>

namespace sympathy {
namespace {

// Derivatives of compositions against the closed forms.
TEST(Dual, ChainRuleMatchesClosedForms) {
  Dual<2> x(0.7);
  x.d = {1.0, 0.0};
  Dual<2> y(-1.3);
  y.d = {0.0, 1.0};
  const auto f = tanh(x * y) / (1.0 + exp(x)) + sqrt(x) * cos(y) - sin(x) / y;
  const double xv = 0.7, yv = -1.3;
  const double t = std::tanh(xv * yv), e = std::exp(xv);
  const double dfdx = (1 - t * t) * yv / (1 + e) - std::tanh(xv * yv) * e / ((1 + e) * (1 + e)) +
                      0.5 / std::sqrt(xv) * std::cos(yv) - std::cos(xv) / yv;
  const double dfdy =
      (1 - t * t) * xv / (1 + e) - std::sqrt(xv) * std::sin(yv) + std::sin(xv) / (yv * yv);
  EXPECT_NEAR(f.d[0], dfdx, 1e-14);
  EXPECT_NEAR(f.d[1], dfdy, 1e-14);
}

}  // namespace
}  // namespace sympathy
