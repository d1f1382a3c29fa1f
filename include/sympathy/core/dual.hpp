// Forward-mode dual numbers with K derivative directions held inline (no heap).
//
// A right-hand side written once as a template evaluates on double for the value and on
// Dual<K> for K directional derivatives at once: seeded with K columns of S it returns J*S,
// seeded with a parameter direction it returns df/dp. Wider products are done in chunks of K.
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

}  // namespace sympathy
