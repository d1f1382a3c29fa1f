// --parent FILE --from-point N|EVENT (orbit, continue; equilibria from equilibria --json): a start
// from a point or an event of a branch an earlier run saved (continue --json), or from a point of a
// two-parameter curve (curve
// --json: its orbit at both parameters' values), AUTO's IRS with a label. The saved orbit's state,
// period, shooting segments and parameter values are the start; Newton corrects it at once (no
// transient), so an unstable orbit restarts as well as a stable one, in the same parameter or
// another. The file is read and checked as the arguments are, before any work.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Dense>

#include "cases/app/arguments.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy::app {

struct SavedStart {
  std::string path;  // --parent
  std::string what;  // --from-point: a point's index, or an event's name (PD1, UZ2, ...)
};

// --parent and --from-point as given (nullopt without --from-point); InputError for
// --from-point without --parent, and beside the options that give a start of their own
// (--start, --initial, --start-data, --switch-at) or move the saved parameter values (--set,
// --params).
std::optional<SavedStart> saved_start(const Arguments& args);

struct SavedOrbit {
  std::string path;         // the branch JSON
  std::string description;  // "FILE, point 12 (rho = 24.5)" for the reports and the JSON's start
  Eigen::VectorXd state0;
  double period = 0.0;
  int segments = 1;        // the shooting segments it was computed on
  ParameterValues values;  // every parameter's, the branch's at the saved point
};

// The saved orbit `start` names in its branch JSON, for `system`; InputError naming the file and
// what is wrong (no such point: the indices it has; no such event: the events it has).
SavedOrbit read_saved_orbit(const SavedStart& start, const OdeSystem& system);

// equilibria --parent EQUILIBRIA.json --from-point N|EVENT: a point (by index) or an event (LP1,
// BP1, HB1, UZ1: its type and number among that type's along the branch) of an earlier run.
struct SavedEquilibrium {
  std::string description;  // "FILE, UZ1 (p2 = 14)"
  Eigen::VectorXd state;
  ParameterValues values;
};
SavedEquilibrium read_saved_equilibrium(const SavedStart& start, const OdeSystem& system);

}  // namespace sympathy::app
