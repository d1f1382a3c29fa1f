#include "sympathy/core/dual.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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

// sin_cos gives what sin and cos give, to the bit (one sincos of the value instead of two): the
// value, and derivatives cos(a) a' and -sin(a) a' (closed form, to the bit too: the same products).
TEST(Dual, SinCosIsSinAndCos) {
  for (double v : {0.0, 0.3, -1.7, 3.0, 1e3}) {
    Dual<3> a(v);
    a.d = {1.0, -0.25, 2.0};
    Dual<3> s, c;
    sin_cos(a, s, c);
    const Dual<3> s1 = sin(a), c1 = cos(a);
    EXPECT_EQ(s.v, s1.v);
    EXPECT_EQ(c.v, c1.v);
    EXPECT_EQ(s.d, s1.d);
    EXPECT_EQ(c.d, c1.d);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(s.d[k], std::cos(v) * a.d[k]);
      EXPECT_EQ(c.d[k], -std::sin(v) * a.d[k]);
    }
    double sd = 0.0, cd = 0.0;
    sin_cos(v, sd, cd);
    EXPECT_EQ(sd, std::sin(v));
    EXPECT_EQ(cd, std::cos(v));
  }
}

// Every function added for equation case files against a central finite difference, step 1e-6:
// truncation error h^2 |f'''| / 6 ~ 1e-12 and rounding 1e-16 / 1e-6 = 1e-10 relative, so a
// tolerance of 1e-8 (relative to max(1, |f'|)) holds them all with room.
TEST(Dual, FunctionsMatchFiniteDifferences) {
  using D = Dual<1>;
  struct Case {
    const char* name;
    D (*dual)(const D&);
    double (*plain)(double);
    double at;
  };
  const Case cases[] = {
      {"tan", [](const D& x) { return tan(x); }, [](double x) { return std::tan(x); }, 0.4},
      {"atan", [](const D& x) { return atan(x); }, [](double x) { return std::atan(x); }, -1.7},
      {"asin", [](const D& x) { return asin(x); }, [](double x) { return std::asin(x); }, 0.3},
      {"acos", [](const D& x) { return acos(x); }, [](double x) { return std::acos(x); }, -0.6},
      {"sinh", [](const D& x) { return sinh(x); }, [](double x) { return std::sinh(x); }, 1.1},
      {"cosh", [](const D& x) { return cosh(x); }, [](double x) { return std::cosh(x); }, -0.8},
      {"abs-", [](const D& x) { return abs(x); }, [](double x) { return std::abs(x); }, -2.5},
      {"abs+", [](const D& x) { return abs(x); }, [](double x) { return std::abs(x); }, 0.5},
      {"erf", [](const D& x) { return erf(x); }, [](double x) { return std::erf(x); }, 0.7},
      {"pow(x, 2.5)", [](const D& x) { return pow(x, 2.5); },
       [](double x) { return std::pow(x, 2.5); }, 1.3},
      {"pow(x, 3) at x < 0", [](const D& x) { return pow(x, D(3.0)); },
       [](double x) { return std::pow(x, 3.0); }, -1.2},
      {"pow(1.7, x)", [](const D& x) { return pow(1.7, x); },
       [](double x) { return std::pow(1.7, x); }, 0.9},
      {"pow(x, x)", [](const D& x) { return pow(x, x); }, [](double x) { return std::pow(x, x); },
       1.4},
      {"atan2(x, 0.3)", [](const D& x) { return atan2(x, D(0.3)); },
       [](double x) { return std::atan2(x, 0.3); }, -0.5},
      {"atan2(0.3, x)", [](const D& x) { return atan2(D(0.3), x); },
       [](double x) { return std::atan2(0.3, x); }, -0.5},
  };
  const double h = 1e-6;
  for (const auto& c : cases) {
    D x(c.at);
    x.d[0] = 1.0;
    const D f = c.dual(x);
    const double fd = (c.plain(c.at + h) - c.plain(c.at - h)) / (2 * h);
    EXPECT_DOUBLE_EQ(f.v, c.plain(c.at)) << c.name;
    EXPECT_NEAR(f.d[0], fd, 1e-8 * std::max(1.0, std::abs(fd))) << c.name;
  }
}

}  // namespace
}  // namespace sympathy
