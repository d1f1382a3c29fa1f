// Stability maps of one periodic orbit in two parameters: the bifurcation curves through every
// event located on its one-parameter branch (bifurcation_curve.hpp), each followed once, and the
// orbit's stability sampled on a grid, which shades the regions the curves bound. The grid's
// orbits come from Newton on the shooting problem, each started from its neighbour in the second
// parameter (the first of each column from the branch's nearest point): one to three iterations
// a point where the orbit changes smoothly, as the paper's synchronized orbits do.
#pragma once

#include <cmath>
#include <functional>
#include <vector>

#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/branch.hpp"

namespace sympathy {

// The curves of every located event of `branch` (LP, BP, PD, NS; not the ends of a branch that
// turned back without a multiplier at +1) in the branch's parameter and `second`, in `options`'
// window: an event that lies on a curve already followed (the same kind, crossing the branch's
// value of `second` there: the second NS point of an NS curve through both) is not followed
// again. A curve that cannot start is kept, with its reason (stop StartFailed). Then one
// generation more: at each point where one of these curves meets another bifurcation (a
// located "NS-LP", "BP-NS", ...) and at each 1:1 and 1:2 resonance of an NS curve (a BP or LP
// curve, a PD curve), the other curve through it, unless already followed; its origin names the
// point.
std::vector<BifurcationCurve> event_curves(const OdeSystem& system, const Branch& branch,
                                           int second, const CurveOptions& options,
                                           const CurveCallbacks& callbacks = {});

// Whether `curve` crosses `value` of its second parameter at `first` of its first: within 1e-4
// relative of it or, where the points lie far apart, within half their distance (the chord
// between two points 0.47 N/m apart missed the anti-phase NS point at k = 56.11 by 0.067 N/m on
// the (k, c) map). With a `rotation` (an NS point's pair angle over 2 pi) the curve's must
// match too, within 2e-3: the row setup's two in-phase NS points at k = 84.93 and 85.01 lie
// closer than the NS curve's points, but their pairs turn by 0.2328 and 0.2401 of a revolution.
// What event_curves asks before following a curve.
bool curve_passes_through(const BifurcationCurve& curve, double first, double value,
                          double rotation = std::nan(""));

struct StabilityGrid {
  std::vector<double> first, second;  // the grid's values of the two parameters
  // Per point [i][j] (second i, first j): the number of multipliers outside the unit circle
  // (0: stable), -1 where no orbit was found; the largest modulus but the trivial one's.
  std::vector<std::vector<int>> unstable_count;
  std::vector<std::vector<double>> max_modulus;
  int failures = 0;  // grid points without an orbit
  double seconds = 0.0;
};

// The orbit's stability on a first_points x second_points grid over the window (both ends
// included), the orbits continued from `branch` (its subspace kept). `stop_requested` (may be
// empty) is polled between columns; an interrupted grid has -1 where it did not reach.
StabilityGrid stability_grid(const OdeSystem& system, const Branch& branch, int second,
                             double first_lower, double first_upper, double second_lower,
                             double second_upper, int first_points, int second_points,
                             const OrbitOptions& options,
                             const std::function<bool()>& stop_requested = {});

}  // namespace sympathy
