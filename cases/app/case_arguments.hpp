// What the commands read from their options (the command line's or Python's keywords, as
// Arguments): the case of either kind with --params and --set (cases/app/loaded_system.hpp), a
// parameter window, and the integrator's and the shooting's options on top of an accuracy preset.
#pragma once

#include "cases/app/arguments.hpp"
#include "cases/app/case_loading.hpp"
#include "cases/app/equation_loading.hpp"
#include "cases/app/loaded_system.hpp"
#include "sympathy/continuation/accuracy.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy::app {

// The case file of positional 0 with --params and --set (a metronome case file).
LoadedCase load_case(const Arguments& args);
// The equation case file of positional 0 with --params, --set and --start-data.
LoadedEquations load_equations(const Arguments& args);

// The case file of positional 0 with --params and --set, and --start-data's recorded period if
// given (its options checked, the recording read before anything is compiled).
LoadedSystem load_system(const Arguments& args);

// --param (required, one of the case's), --from and --to (required, different) and --at (if
// given); InputError naming the option. Their range is LoadedSystem::check_range's.
ParameterWindow parameter_window(const Arguments& args, const LoadedSystem& c);

// --threads N as given (ShootingOptions::validate checks it: 1 to 256), by default one per core;
// the shooting uses at most as many as it has segments, and its result does not depend on them.
int segment_threads(const Arguments& args);
// The preset --accuracy names (Default without it).
Accuracy accuracy(const Arguments& args);
// The integrator options --rtol, --atol, --method and --sensitivities on top of `defaults` (for
// orbit and continue: the accuracy preset's); without --linear-solver, defaults.linear_solver (by
// default Automatic: the flow chooses, see LinearSolver).
FlowOptions flow_options(const Arguments& args, FlowOptions defaults);
// The same for an orbit's shooting flow (orbit, continue, curve): a --method given turns off the
// presets' switch to BDF where the start is stiff (OrbitOptions::switch_when_stiff), and the
// transient takes the shooting's linear solver.
void shooting_flow_options(const Arguments& args, OrbitOptions& options);

}  // namespace sympathy::app
