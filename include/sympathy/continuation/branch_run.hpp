// The branch workflow, as one call: the orbit at the first parameter value (found from a start
// state by a transient and Newton, or given), then pseudo-arclength continuation one way, or both
// ways from an interior value joined into one Branch in parameter order, its events ordered
// along it, every point described (OrbitDescriber) and handed to the callbacks as it is found.
// The CLI, study files, the bench and library users all run branches through here.
#pragma once

#include <optional>
#include <string>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/invariant_subspace.hpp"

namespace sympathy {

// What to continue (BifurcationKit's problem): which parameter, from where to where, and from
// which start. Options (ContinuationOptions) and callbacks are separate values.
struct BranchProblem {
  int parameter = -1;      // index of the continued named parameter
  ParameterValues values;  // every parameter's value; the continued one is set to the first value
  double from = 0.0;       // the branch runs from `from` to `to` ...
  double to = 0.0;
  std::optional<double> at;     // ... or starts at `at` (strictly between them) and goes both ways
  Eigen::VectorXd start_state;  // the transient starts here (ignored when start_orbit is given)
  InvariantSubspace subspace;   // ... and stays in it (a symmetric orbit, however unstable)
  std::optional<PeriodicOrbit> start_orbit;  // a converged orbit at the first value instead
  // A period guess for start_state (a recorded period, recorded_period.hpp): Newton from there
  // at once, without the transient. For a periodically forced system, the forcing's period
  // (required unless start_orbit is given or the system declares it, OdeSystem::forcing_period:
  // then its transient runs over whole periods of the forcing, as find_periodic_orbit's).
  std::optional<double> start_period;
  std::string start_name = "start";  // how messages name the start

  // What is wrong with it for `system` (empty when nothing): the field and what was expected.
  std::string problem_with(const OdeSystem& system) const;
  double first_value() const { return at ? *at : from; }
};

// Points reach on_point with their index along the joined branch (negative on the backward part
// of a two-way run) and their description.
Branch continue_branch(const OdeSystem& system, const BranchProblem& problem,
                       const ContinuationOptions& options,
                       const ContinuationCallbacks& callbacks = {},
                       const OrbitDescriber* describer = nullptr);

// The located orbit of each event described (Bifurcation::description), at `values` with the
// branch's parameter at the event's value, from the event's samples where it carries them (then
// emptied) or one plain period: what continue_branch does for its events, for a branch made
// otherwise (switch_branch, a family born at a Hopf point).
void describe_events(Branch& branch, const OdeSystem& system, const OrbitDescriber& describer,
                     const ParameterValues& values, const InvariantSubspace& subspace = {});

}  // namespace sympathy
