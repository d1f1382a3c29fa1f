// pi, 2 pi, a planar orbit's other multiplier and multipliers sorted by modulus for the tests'
// exact answers, defined once: the tests compile in batches (a unity build), where a constant of
// the same name in two files of one batch would be defined twice.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "sympathy/floquet/floquet.hpp"

namespace sympathy::testing {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2 * std::numbers::pi;

// The real part of the first multiplier that is not the trivial one (NaN if there is none): the
// one other multiplier of a planar orbit.
inline double nontrivial_multiplier(const FloquetAnalysis& f) {
  for (const auto& m : f.multipliers)
    if (!m.trivial) return m.value.real();
  return NAN;
}

// Multipliers (or eigenvalues) largest modulus first, a pair's positive imaginary part first:
// an order two computations of the same orbit share, to compare them entry by entry.
inline std::vector<std::complex<double>> by_modulus(std::vector<std::complex<double>> values) {
  std::sort(values.begin(), values.end(), [](const auto& a, const auto& b) {
    return std::abs(a) > std::abs(b) || (std::abs(a) == std::abs(b) && a.imag() > b.imag());
  });
  return values;
}
inline std::vector<std::complex<double>> by_modulus(const FloquetAnalysis& f) {
  std::vector<std::complex<double>> values;
  for (const auto& mu : f.multipliers) values.push_back(mu.value);
  return by_modulus(std::move(values));
}

}  // namespace sympathy::testing
