// Detecting bifurcations between two consecutive branch points, from test functions: the sign of
// the tangent's parameter component for folds (LP), and |mu| - 1 of each followed multiplier for
// the rest: real through +1 without a fold a branch point (BP), real through -1 a period doubling
// (PD), a complex pair a Neimark-Sacker point (NS). Crossings of equal multipliers at once (as
// symmetric systems have) make one event with its multiplicity. Each event is located by the
// caller's locator and flagged untrusted where the trivial multiplier's error is above the limit.
#pragma once

#include <algorithm>
#include <complex>
#include <functional>
#include <string>
#include <vector>

#include "sympathy/continuation/multiplier_tracking.hpp"

namespace sympathy {

// Locates one event between a and b, given its type, multiplicity and the multiplier followed
// across at a and at b (zero for a fold); `beside_fold`: a branch point in a step that holds a fold
// too, crossed by the fold's own multiplier (location.hpp).
using Locator =
    std::function<Bifurcation(BifurcationType type, int multiplicity, std::complex<double> mu_a,
                              std::complex<double> mu_b, bool beside_fold)>;

// Whether a turn of the tangent with no multiplier seen through +1 is the family's end (its
// orbits shrinking into an equilibrium at a Hopf point), where nothing is to be located beside it.
using TurnEnds = std::function<bool(const Bifurcation& turn)>;

// What an event's note says of multipliers that cross together ("3 complex pairs cross
// together"); empty for one.
std::string together_note(BifurcationType type, int multiplicity);

// The trivial-multiplier error above which an event is not trusted. An event located by its
// multipliers (BP, PD, NS) rests on their accuracy: `absolute` (ContinuationOptions::trust_limit).
// One located without them (a fold on the tangent, a user point at its parameter value) rests on
// the corrector, and its multipliers only show that nothing but the integration's noise is in the
// monodromy, whose floor grows with |M| = |D^-1 M D|_inf (PeriodicOrbit::monodromy_growth). On
// AUTO's demos at rtol 1e-11 (2,800 points of 28 runs) the trivial errors are a median 0.05-24
// and at most 3,400 rtol |M|: the limit is kNoiseFloor rtol |M|, at least `absolute` and at most
// kCeiling times it (beyond, the orbit itself is known no better than the noise: near AUTO's
// homoclinic orbits |M| reaches 1e14). AUTO's tor has its fold at T 49.36 (rn = -0.796909055, to
// 1e-10 of an independent shooting) with an error of 6.9e-6, 211 rtol |M| (|M| 3,267).
struct TrustLimit {
  static constexpr double kNoiseFloor = 1000.0, kCeiling = 100.0;
  double absolute = 1e-6;
  double rtol = 0.0;  // the shooting flow's
  double without_multipliers(double monodromy_growth) const {
    return std::clamp(kNoiseFloor * rtol * monodromy_growth, absolute, kCeiling * absolute);
  }
};

// The events between a and b, located, in order along the branch.
std::vector<Bifurcation> detect(const TrackedMultipliers& tracked, const ContinuationPoint& a,
                                const ContinuationPoint& b, const TrustLimit& trust,
                                const Locator& locate, const TurnEnds& turn_ends = nullptr);

}  // namespace sympathy
