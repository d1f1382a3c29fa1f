// Detecting bifurcations between two consecutive branch points, from test functions: the sign of
// the tangent's parameter component for folds (LP), and |mu| - 1 of each followed multiplier for
// the rest: real through +1 without a fold a branch point (BP), real through -1 a period doubling
// (PD), a complex pair a Neimark-Sacker point (NS). Crossings of equal multipliers at once (as
// symmetric systems have) make one event with its multiplicity. Each event is located by the
// caller's locator and flagged untrusted where the trivial multiplier's error is above the limit.
#pragma once

#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "sympathy/continuation/multiplier_tracking.hpp"

namespace sympathy {

// Locates one event between a and b, given its type, multiplicity and the multiplier followed
// across at a and at b (zero for a fold).
using Locator = std::function<Bifurcation(BifurcationType type, int multiplicity,
                                          std::complex<double> mu_a, std::complex<double> mu_b)>;

// What an event's note says of multipliers that cross together ("3 complex pairs cross
// together"); empty for one.
std::string together_note(BifurcationType type, int multiplicity);

// The events between a and b, located, in order along the branch.
std::vector<Bifurcation> detect(const TrackedMultipliers& tracked, const ContinuationPoint& a,
                                const ContinuationPoint& b, double trust_limit,
                                const Locator& locate);

}  // namespace sympathy
