// pi, 2 pi and a planar orbit's other multiplier for the tests' exact answers, defined once: the
// tests compile in batches (a unity build), where a constant of the same name in two files of one
// batch would be defined twice.
#pragma once

#include <cmath>
#include <numbers>

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

}  // namespace sympathy::testing
