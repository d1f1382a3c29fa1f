// The equilibria's part of a stability map: the fold (LP) and Hopf (HB) curves through every
// event located on a branch of equilibria, each followed once, and the curves the codimension-two
// points on them start (as AUTO's and MatCont's users draw a two-parameter diagram: the LP and HB
// loci with their BT, ZH, HH points, beside the cycles' curves of stability_map.hpp).
#pragma once

#include <cmath>
#include <vector>

#include "sympathy/continuation/equilibrium_curve.hpp"

namespace sympathy {

// Whether `curve` crosses `value` of its second parameter at `first` of its first (as the
// cycles' curve_passes_through); with a `kappa` (a Hopf curve's omega^2 there) the curve's must
// match too, within 1% of the largest |kappa| along it: the double Hopf form's two Hopf curves
// through its HH point have kappa 1 and 2 there.
bool curve_passes_through(const EquilibriumCurve& curve, double first, double value,
                          double kappa = std::nan(""));

// The curves of every located LP and HB of `branch` in the branch's parameter and `second`, in
// `options`' window: an event that lies on a curve already followed (the second HB of a Hopf
// curve that the branch crosses twice) is not followed again. A curve that cannot start is kept
// with its reason (stop StartFailed). Then one generation more: at each BT, ZH and HH on these
// curves, the other curve through it (continue_from_codimension_two), unless already followed;
// its origin names the point. (At a cusp the fold curve goes on through it: nothing new starts.)
std::vector<EquilibriumCurve> equilibrium_event_curves(
    const OdeSystem& system, const EquilibriumBranch& branch, int second,
    const EquilibriumCurveOptions& options, const EquilibriumCurveCallbacks& callbacks = {});

}  // namespace sympathy
