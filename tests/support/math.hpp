// pi and 2 pi for the tests' exact answers, defined once: the tests compile in batches (a unity
// build), where a constant of the same name in two files of one batch would be defined twice.
#pragma once

#include <numbers>

namespace sympathy::testing {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2 * std::numbers::pi;

}  // namespace sympathy::testing
