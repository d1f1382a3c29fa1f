// Following the Floquet multipliers from one branch point to the next. Each multiplier of a is
// first predicted at b by extrapolating its motion from the point before a (moved by the ratio of
// the steps), then the predictions are paired with b's multipliers by least total distance
// (Kuhn-Munkres). How doubtful the pairing is, is measured only near the unit circle (where a
// wrong pairing could hide or invent a crossing) and only against gaps above 0.01 (collisions,
// where two real multipliers meet and split into a complex pair, are not ambiguities).
#pragma once

#include <complex>
#include <utility>
#include <vector>

#include "sympathy/continuation/branch.hpp"

namespace sympathy {

// The multipliers that can cross the unit circle: neither the trivial one nor those a family of
// orbits forces to 1 (the Floquet analysis keeps the two kinds apart, even where one of these
// crosses 1 among them).
std::vector<Multiplier> nontrivial(const FloquetAnalysis& f);

// A real multiplier, to a millionth of its modulus: what crosses +1 (LP, BP) or -1 (PD) rather
// than in a complex pair (NS).
inline bool is_real(std::complex<double> mu) {
  return std::abs(mu.imag()) <= 1e-6 * std::abs(mu);
}

struct TrackedMultipliers {
  std::vector<std::pair<Multiplier, Multiplier>> pairs;  // (at a, at b)
  // The largest distance from a prediction to its match, relative to the gap from that match to
  // its nearest neighbour at b: above 1/2 the pairing is doubtful.
  double ambiguity = 0.0;
};

// The nontrivial multipliers of a followed to b, their motion predicted from `before` (may be
// null: no prediction).
TrackedMultipliers track(const ContinuationPoint* before, const ContinuationPoint& a,
                         const ContinuationPoint& b);

}  // namespace sympathy
