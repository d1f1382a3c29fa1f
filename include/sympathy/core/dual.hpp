// Forward-mode dual numbers with K derivative directions held inline (no heap).
//
// A right-hand side written once as a template evaluates on double for the value and on
// Dual<K> for K directional derivatives at once: seeded with K columns of S it returns J*S,
// seeded with a parameter direction it returns df/dp. Wider products are done in chunks of K.
//
// The functions below are those of equation case files (cases/expression.hpp) and what a user's
// model reaches for: sin cos tan exp log sqrt tanh atan asin acos atan2 sinh cosh pow abs erf,
// each held against central finite differences in tests/core/dual_test.cpp. Where a function has
// no derivative (abs at 0) the one-sided value of the upper branch is taken (abs'(0) = 1), as
// AUTO's and Julia's ForwardDiff do.
#pragma once

#include <array>
#include <cmath>

namespace sympathy {

template <int K>
struct Dual {
  double v = 0.0;
  std::array<double, K> d{};

  Dual() = default;
  Dual(double value) : v(value) {}  // NOLINT: implicit, constants mix freely with duals

  Dual& operator+=(const Dual& b) {
    v += b.v;
    for (int k = 0; k < K; ++k) d[k] += b.d[k];
    return *this;
  }
  Dual& operator-=(const Dual& b) {
    v -= b.v;
    for (int k = 0; k < K; ++k) d[k] -= b.d[k];
    return *this;
  }
  Dual& operator*=(const Dual& b) {
    for (int k = 0; k < K; ++k) d[k] = d[k] * b.v + v * b.d[k];
    v *= b.v;
    return *this;
  }
  Dual& operator/=(const Dual& b) {
    const double inv = 1.0 / b.v;
    v *= inv;
    for (int k = 0; k < K; ++k) d[k] = (d[k] - v * b.d[k]) * inv;
    return *this;
  }
  Dual& operator+=(double b) {
    v += b;
    return *this;
  }
  Dual& operator-=(double b) {
    v -= b;
    return *this;
  }
  Dual& operator*=(double b) {
    v *= b;
    for (int k = 0; k < K; ++k) d[k] *= b;
    return *this;
  }
  Dual& operator/=(double b) { return *this *= (1.0 / b); }
};

// Value of a double or of a dual: lets templated code branch on values.
inline double value_of(double x) {
  return x;
}
template <int K>
double value_of(const Dual<K>& x) {
  return x.v;
}

template <int K>
Dual<K> operator-(Dual<K> a) {
  a.v = -a.v;
  for (int k = 0; k < K; ++k) a.d[k] = -a.d[k];
  return a;
}
template <int K>
Dual<K> operator+(Dual<K> a, const Dual<K>& b) {
  return a += b;
}
template <int K>
Dual<K> operator-(Dual<K> a, const Dual<K>& b) {
  return a -= b;
}
template <int K>
Dual<K> operator*(Dual<K> a, const Dual<K>& b) {
  return a *= b;
}
template <int K>
Dual<K> operator/(Dual<K> a, const Dual<K>& b) {
  return a /= b;
}
template <int K>
Dual<K> operator+(Dual<K> a, double b) {
  return a += b;
}
template <int K>
Dual<K> operator+(double a, Dual<K> b) {
  return b += a;
}
template <int K>
Dual<K> operator-(Dual<K> a, double b) {
  return a -= b;
}
template <int K>
Dual<K> operator-(double a, const Dual<K>& b) {
  return -b + a;
}
template <int K>
Dual<K> operator*(Dual<K> a, double b) {
  return a *= b;
}
template <int K>
Dual<K> operator*(double a, Dual<K> b) {
  return b *= a;
}
template <int K>
Dual<K> operator/(Dual<K> a, double b) {
  return a /= b;
}
template <int K>
Dual<K> operator/(double a, const Dual<K>& b) {
  Dual<K> r(a / b.v);
  const double s = -r.v / b.v;
  for (int k = 0; k < K; ++k) r.d[k] = s * b.d[k];
  return r;
}

// Chain rule: f(a) with f'(a) given.
template <int K>
Dual<K> chain(const Dual<K>& a, double f, double df) {
  Dual<K> r(f);
  for (int k = 0; k < K; ++k) r.d[k] = df * a.d[k];
  return r;
}

template <int K>
Dual<K> sin(const Dual<K>& a) {
  return chain(a, std::sin(a.v), std::cos(a.v));
}
template <int K>
Dual<K> cos(const Dual<K>& a) {
  return chain(a, std::cos(a.v), -std::sin(a.v));
}
// sin and cos of one argument together: a model that wants both pays one sin and one cos of the
// value (the two calls above would each take both; as bit-exact as they are).
inline void sin_cos(double a, double& s, double& c) {
  s = std::sin(a);
  c = std::cos(a);
}
template <int K>
void sin_cos(const Dual<K>& a, Dual<K>& s, Dual<K>& c) {
  const double sv = std::sin(a.v), cv = std::cos(a.v);
  s = chain(a, sv, cv);
  c = chain(a, cv, -sv);
}
template <int K>
Dual<K> tanh(const Dual<K>& a) {
  const double t = std::tanh(a.v);
  return chain(a, t, 1.0 - t * t);
}
template <int K>
Dual<K> exp(const Dual<K>& a) {
  const double e = std::exp(a.v);
  return chain(a, e, e);
}
template <int K>
Dual<K> log(const Dual<K>& a) {
  return chain(a, std::log(a.v), 1.0 / a.v);
}
template <int K>
Dual<K> sqrt(const Dual<K>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s);
}

template <int K>
Dual<K> tan(const Dual<K>& a) {
  const double t = std::tan(a.v);
  return chain(a, t, 1.0 + t * t);
}
template <int K>
Dual<K> atan(const Dual<K>& a) {
  return chain(a, std::atan(a.v), 1.0 / (1.0 + a.v * a.v));
}
template <int K>
Dual<K> asin(const Dual<K>& a) {
  return chain(a, std::asin(a.v), 1.0 / std::sqrt(1.0 - a.v * a.v));
}
template <int K>
Dual<K> acos(const Dual<K>& a) {
  return chain(a, std::acos(a.v), -1.0 / std::sqrt(1.0 - a.v * a.v));
}
template <int K>
Dual<K> sinh(const Dual<K>& a) {
  return chain(a, std::sinh(a.v), std::cosh(a.v));
}
template <int K>
Dual<K> cosh(const Dual<K>& a) {
  return chain(a, std::cosh(a.v), std::sinh(a.v));
}
template <int K>
Dual<K> abs(const Dual<K>& a) {
  return chain(a, std::abs(a.v), a.v < 0.0 ? -1.0 : 1.0);
}
template <int K>
Dual<K> erf(const Dual<K>& a) {
  // d/dx erf(x) = 2 / sqrt(pi) exp(-x^2)
  return chain(a, std::erf(a.v), 1.1283791670955126 * std::exp(-a.v * a.v));
}
// atan2(y, x), the angle of (x, y): d = (x dy - y dx) / (x^2 + y^2).
template <int K>
Dual<K> atan2(const Dual<K>& y, const Dual<K>& x) {
  Dual<K> r(std::atan2(y.v, x.v));
  const double inv = 1.0 / (x.v * x.v + y.v * y.v);
  for (int k = 0; k < K; ++k) r.d[k] = (x.v * y.d[k] - y.v * x.d[k]) * inv;
  return r;
}
// a^b: d = b a^(b-1) da + a^b log(a) db. The second term only where b varies, so that a
// negative base with a constant exponent (x^3 at x < 0) has its derivative, not NaN.
template <int K>
Dual<K> pow(const Dual<K>& a, const Dual<K>& b) {
  const double f = std::pow(a.v, b.v);
  Dual<K> r(f);
  const double da = b.v == 0.0 ? 0.0 : b.v * std::pow(a.v, b.v - 1.0);
  bool varies = false;
  for (int k = 0; k < K; ++k) varies = varies || b.d[k] != 0.0;
  const double db = varies ? f * std::log(a.v) : 0.0;
  for (int k = 0; k < K; ++k) r.d[k] = da * a.d[k] + (varies ? db * b.d[k] : 0.0);
  return r;
}
template <int K>
Dual<K> pow(const Dual<K>& a, double b) {
  return chain(a, std::pow(a.v, b), b == 0.0 ? 0.0 : b * std::pow(a.v, b - 1.0));
}
template <int K>
Dual<K> pow(double a, const Dual<K>& b) {
  const double f = std::pow(a, b.v);
  return chain(b, f, f * std::log(a));
}

}  // namespace sympathy
