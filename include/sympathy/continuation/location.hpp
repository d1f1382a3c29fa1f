// Locating one bifurcation between two branch points a and b: a bracketing secant (Illinois) on
// the event's test function (the tangent's parameter component for a fold; |mu| - 1 of the
// multiplier followed across, by continuity, otherwise), in arclength along a's tangent, until
// the bracket is narrower than the tolerance relative to the parameter. Each probe closes the
// bracket from the inside by at least half the tolerance, so a root next to one end is bracketed
// at once instead of crept up on (5-6 corrections per event on the paper's branches).
#pragma once

#include <complex>
#include <functional>
#include <optional>
#include <string>

#include "sympathy/continuation/branch.hpp"

namespace sympathy {

// The branch point at arclength s from a, along a's tangent and in a's section; nullopt with the
// reason in `why` when it cannot be corrected. The location makes no point itself: the run that
// owns the corrector gives this.
using PointAt = std::function<std::optional<ContinuationPoint>(double s, std::string& why)>;

// `tolerance`: relative, in the parameter (ContinuationOptions::location_tolerance), to the
// parameter's size but at least `scale_floor` (the continuation passes a hundredth of its range:
// a point at a parameter value near 0, a Hopf end at mu = 0, needs no 1e-8 of nothing).
// `beside_fold`: a branch point in a step that holds a fold too, crossed by the multiplier that
// crosses +1 at the fold: |mu| - 1 changes sign at both, so that it is |mu| - 1 times the sign of
// the tangent's parameter component (relative to a's) that changes sign at the branch point
// alone (at the fold both factors vanish; AUTO's branch-point test is such a product).
Bifurcation locate(const ContinuationPoint& a, const ContinuationPoint& b, BifurcationType type,
                   int multiplicity, std::complex<double> mu_a, std::complex<double> mu_b,
                   double tolerance, double scale_floor, const PointAt& point_at,
                   bool beside_fold = false);

}  // namespace sympathy
