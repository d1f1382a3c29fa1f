// Truncated Taylor series in one variable with complex coefficients: what f(x + s v) is to order
// N in s when a right-hand side written once as a template (core/autodiff_system.hpp) runs on
// Jet<N>. Its k-th coefficient is D^k f(x)(v, ..., v) / k!, the derivative tensor of order k on
// k copies of v: exact, where differences of differences lose a digit per order (a fifth
// derivative by differences of f_x keeps about three). The normal-form coefficients of
// equilibria need f's derivatives up to the fifth (the second Lyapunov coefficient at a
// generalized Hopf point); continuation/multilinear_forms.hpp makes tensors on different
// vectors from these diagonal ones.
//
// The coefficients are complex because the directions are (Hopf eigenvectors): with x real, the
// constant term stays real, and value_of (the branches of abs, min, max and the escapement's
// zones) reads it. The functions are those of core/dual.hpp, by the recurrences of Griewank and
// Walther, Evaluating Derivatives, 2nd ed., ch. 13 (each held against dual numbers and closed
// forms in tests/core/jet_test.cpp).
#pragma once

#include <array>
#include <cmath>
#include <complex>
#include <numbers>

namespace sympathy {

template <int N>
struct Jet {
  using Complex = std::complex<double>;
  std::array<Complex, N + 1> c{};

  Jet() = default;
  Jet(double value) { c[0] = value; }  // NOLINT: implicit, constants mix freely with jets

  Jet& operator+=(const Jet& b) {
    for (int k = 0; k <= N; ++k) c[k] += b.c[k];
    return *this;
  }
  Jet& operator-=(const Jet& b) {
    for (int k = 0; k <= N; ++k) c[k] -= b.c[k];
    return *this;
  }
  Jet& operator*=(const Jet& b) {
    Jet r;
    for (int k = 0; k <= N; ++k)
      for (int j = 0; j <= k; ++j) r.c[k] += c[j] * b.c[k - j];
    return *this = r;
  }
  Jet& operator/=(const Jet& b) {
    // c = a / b: a_k = sum_j c_j b_(k-j).
    Jet r;
    for (int k = 0; k <= N; ++k) {
      Complex s = c[k];
      for (int j = 0; j < k; ++j) s -= r.c[j] * b.c[k - j];
      r.c[k] = s / b.c[0];
    }
    return *this = r;
  }
  Jet& operator+=(double b) {
    c[0] += b;
    return *this;
  }
  Jet& operator-=(double b) {
    c[0] -= b;
    return *this;
  }
  Jet& operator*=(double b) {
    for (auto& x : c) x *= b;
    return *this;
  }
  Jet& operator/=(double b) { return *this *= (1.0 / b); }
};

template <int N>
double value_of(const Jet<N>& x) {
  return x.c[0].real();
}

template <int N>
Jet<N> operator-(Jet<N> a) {
  for (auto& x : a.c) x = -x;
  return a;
}
template <int N>
Jet<N> operator+(Jet<N> a, const Jet<N>& b) {
  return a += b;
}
template <int N>
Jet<N> operator-(Jet<N> a, const Jet<N>& b) {
  return a -= b;
}
template <int N>
Jet<N> operator*(Jet<N> a, const Jet<N>& b) {
  return a *= b;
}
template <int N>
Jet<N> operator/(Jet<N> a, const Jet<N>& b) {
  return a /= b;
}
template <int N>
Jet<N> operator+(Jet<N> a, double b) {
  return a += b;
}
template <int N>
Jet<N> operator+(double a, Jet<N> b) {
  return b += a;
}
template <int N>
Jet<N> operator-(Jet<N> a, double b) {
  return a -= b;
}
template <int N>
Jet<N> operator-(double a, const Jet<N>& b) {
  return -b + a;
}
template <int N>
Jet<N> operator*(Jet<N> a, double b) {
  return a *= b;
}
template <int N>
Jet<N> operator*(double a, Jet<N> b) {
  return b *= a;
}
template <int N>
Jet<N> operator/(Jet<N> a, double b) {
  return a /= b;
}
template <int N>
Jet<N> operator/(double a, const Jet<N>& b) {
  return Jet<N>(a) /= b;
}

namespace jet_detail {

// The series of a' (its coefficients shifted down, times their order) and of the integral of d
// with constant term y0: y = y0 + integral of d ds, to order N.
template <int N>
Jet<N> derivative(const Jet<N>& a) {
  Jet<N> d;
  for (int k = 1; k <= N; ++k) d.c[k - 1] = static_cast<double>(k) * a.c[k];
  return d;
}
template <int N>
Jet<N> integral(const Jet<N>& d, double y0) {
  Jet<N> y(y0);
  for (int k = 1; k <= N; ++k) y.c[k] = d.c[k - 1] / static_cast<double>(k);
  return y;
}

// y and z with y' = z a', z' = sign y a' (sin and cos: sign -1; sinh and cosh: +1).
template <int N>
void paired(const Jet<N>& a, double y0, double z0, double sign, Jet<N>& y, Jet<N>& z) {
  y = Jet<N>(y0);
  z = Jet<N>(z0);
  for (int k = 1; k <= N; ++k) {
    std::complex<double> sy = 0.0, sz = 0.0;
    for (int j = 1; j <= k; ++j) {
      sy += static_cast<double>(j) * a.c[j] * z.c[k - j];
      sz += static_cast<double>(j) * a.c[j] * y.c[k - j];
    }
    y.c[k] = sy / static_cast<double>(k);
    z.c[k] = sign * sz / static_cast<double>(k);
  }
}

}  // namespace jet_detail

template <int N>
Jet<N> exp(const Jet<N>& a) {
  Jet<N> y(std::exp(a.c[0].real()));
  for (int k = 1; k <= N; ++k) {
    std::complex<double> s = 0.0;
    for (int j = 1; j <= k; ++j) s += static_cast<double>(j) * a.c[j] * y.c[k - j];
    y.c[k] = s / static_cast<double>(k);
  }
  return y;
}
template <int N>
Jet<N> log(const Jet<N>& a) {
  Jet<N> y(std::log(a.c[0].real()));
  for (int k = 1; k <= N; ++k) {
    std::complex<double> s = a.c[k];
    for (int j = 1; j < k; ++j) s -= static_cast<double>(j) / k * y.c[j] * a.c[k - j];
    y.c[k] = s / a.c[0];
  }
  return y;
}
template <int N>
Jet<N> sqrt(const Jet<N>& a) {
  Jet<N> y(std::sqrt(a.c[0].real()));
  for (int k = 1; k <= N; ++k) {
    std::complex<double> s = a.c[k];
    for (int j = 1; j < k; ++j) s -= y.c[j] * y.c[k - j];
    y.c[k] = s / (2.0 * y.c[0]);
  }
  return y;
}
template <int N>
void sin_cos(const Jet<N>& a, Jet<N>& s, Jet<N>& c) {
  const double v = a.c[0].real();
  jet_detail::paired(a, std::sin(v), std::cos(v), -1.0, s, c);
}
template <int N>
Jet<N> sin(const Jet<N>& a) {
  Jet<N> s, c;
  sin_cos(a, s, c);
  return s;
}
template <int N>
Jet<N> cos(const Jet<N>& a) {
  Jet<N> s, c;
  sin_cos(a, s, c);
  return c;
}
template <int N>
Jet<N> tan(const Jet<N>& a) {
  Jet<N> s, c;
  sin_cos(a, s, c);
  return s / c;
}
template <int N>
Jet<N> sinh(const Jet<N>& a) {
  const double v = a.c[0].real();
  Jet<N> s, c;
  jet_detail::paired(a, std::sinh(v), std::cosh(v), 1.0, s, c);
  return s;
}
template <int N>
Jet<N> cosh(const Jet<N>& a) {
  const double v = a.c[0].real();
  Jet<N> s, c;
  jet_detail::paired(a, std::sinh(v), std::cosh(v), 1.0, s, c);
  return c;
}
template <int N>
Jet<N> tanh(const Jet<N>& a) {
  // t' = u a' with u = 1 - t^2, u's coefficient m known once t's up to m are.
  Jet<N> t(std::tanh(a.c[0].real())), u;
  u.c[0] = 1.0 - t.c[0] * t.c[0];
  for (int k = 1; k <= N; ++k) {
    std::complex<double> s = 0.0;
    for (int j = 1; j <= k; ++j) s += static_cast<double>(j) * a.c[j] * u.c[k - j];
    t.c[k] = s / static_cast<double>(k);
    std::complex<double> sq = 0.0;
    for (int i = 0; i <= k; ++i) sq += t.c[i] * t.c[k - i];
    u.c[k] = -sq;
  }
  return t;
}
template <int N>
Jet<N> atan(const Jet<N>& a) {
  return jet_detail::integral(jet_detail::derivative(a) / (1.0 + a * a), std::atan(a.c[0].real()));
}
template <int N>
Jet<N> asin(const Jet<N>& a) {
  return jet_detail::integral(jet_detail::derivative(a) / sqrt(1.0 - a * a),
                              std::asin(a.c[0].real()));
}
template <int N>
Jet<N> acos(const Jet<N>& a) {
  return jet_detail::integral(-jet_detail::derivative(a) / sqrt(1.0 - a * a),
                              std::acos(a.c[0].real()));
}
template <int N>
Jet<N> erf(const Jet<N>& a) {
  return jet_detail::integral(
      2.0 / std::sqrt(std::numbers::pi) * exp(-(a * a)) * jet_detail::derivative(a),
      std::erf(a.c[0].real()));
}
template <int N>
Jet<N> atan2(const Jet<N>& y, const Jet<N>& x) {
  const Jet<N> d =
      (x * jet_detail::derivative(y) - y * jet_detail::derivative(x)) / (x * x + y * y);
  return jet_detail::integral(d, std::atan2(y.c[0].real(), x.c[0].real()));
}
// abs'(0) = 1, the upper branch, as for dual numbers.
template <int N>
Jet<N> abs(const Jet<N>& a) {
  return a.c[0].real() >= 0.0 ? a : -a;
}
// a^b: repeated products for a small whole b (exact where a's value is 0: x^2 at x = 0); else
// a^b = exp(b log a)'s recurrence, y' a = b y a', which needs a's value nonzero.
template <int N>
Jet<N> pow(const Jet<N>& a, double b) {
  if (b == std::floor(b) && std::abs(b) <= 16.0) {
    Jet<N> r(1.0);
    for (int i = 0; i < static_cast<int>(std::abs(b)); ++i) r *= a;
    return b < 0 ? 1.0 / r : r;
  }
  Jet<N> y(std::pow(a.c[0].real(), b));
  for (int k = 1; k <= N; ++k) {
    std::complex<double> s = 0.0;
    for (int j = 1; j <= k; ++j) s += (b * j - (k - j)) * a.c[j] * y.c[k - j];
    y.c[k] = s / (static_cast<double>(k) * a.c[0]);
  }
  return y;
}
// An exponent without a series (a parameter, or a constant of an equation file, which reach the
// generated code as jets too) takes the branch above.
template <int N>
Jet<N> pow(const Jet<N>& a, const Jet<N>& b) {
  bool constant = b.c[0].imag() == 0.0;
  for (int k = 1; k <= N; ++k) constant = constant && b.c[k] == 0.0;
  return constant ? pow(a, b.c[0].real()) : exp(b * log(a));
}
template <int N>
Jet<N> pow(double a, const Jet<N>& b) {
  return exp(b * std::log(a));
}

}  // namespace sympathy
