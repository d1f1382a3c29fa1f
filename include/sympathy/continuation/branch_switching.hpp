// Branch switching: the branch born at a located branch point (BP) or period doubling (PD).
//
// At a BP the shooting equations F(x, p) = 0 have two branches through the point, and the
// null space of [F_x F_p] there is two-dimensional: the old branch's tangent and the new
// branch's. At a PD the orbit traversed twice is a solution of period 2T whose monodromy M^2 has
// the multiplier (-1)^2 = 1, and the period-2T shooting equations have the same structure: the
// old orbits (twice round) and the doubled-period orbits born there. So both switches are one:
// the new direction is the vector of that null space (found from the SVD of the Jacobian in the
// branch's scaled norm; widened by a family's directions where there are some) nearest to the
// critical multiplier's eigenvector, orthogonal to the old branch's tangent (BP) or with no
// parameter component (PD: the doubled orbits are born in a pitchfork, p - p_PD ~ s^2; the
// symmetry-breaking BP of the paper's cases is one too). At a BP that breaks no declared symmetry
// (two families crossing at an angle, AUTO's lcbp) the new branch is not orthogonal to the old
// one: its tangent is the root of the algebraic branching equation (psi^T F_yy on the null
// space, psi the left null vector; second derivatives by differences of Jacobians) least
// parallel to the old tangent. One step along it is corrected (the
// arclength condition along the new direction is regular there, where the point itself is
// singular), and the new branch is continued both ways from that point: away from the event,
// and back through it onto its other half (for a pitchfork, the mirror image).
#pragma once

#include <string>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/continuation.hpp"

namespace sympathy {

// What the switch computed, for reports and tests.
struct SwitchStart {
  PeriodicOrbit base;               // the orbit at the event (period 2T for a PD)
  Eigen::VectorXd critical;         // the critical eigenvector (state), unit length
  Eigen::VectorXd direction;        // the new branch's unit tangent (unknowns, parameter), scaled
  double old_branch_component = 0;  // |<old tangent, first step>| / step: near 0 on a new branch
  double off_event = 0;             // the first point's distance from the event, scaled norm
};

// The branch born at `event` of `branch` (of `system`, continued in branch.parameter), run with
// `options` (its bounds the window) and `callbacks`. Throws std::invalid_argument unless the
// event is a located BP or PD of that branch, and std::runtime_error where no step off the event
// can be corrected or the step falls back onto the old branch. `start` (may be null) receives
// what the switch computed. The new branch's `origin` names the event.
Branch switch_branch(const OdeSystem& system, const Branch& branch, const Bifurcation& event,
                     const ContinuationOptions& options,
                     const ContinuationCallbacks& callbacks = {}, SwitchStart* start = nullptr);

}  // namespace sympathy
