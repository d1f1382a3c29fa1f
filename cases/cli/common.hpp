// What every subcommand shares: the options that load a case (read by the application layer,
// app/case_loading.hpp), integrator options from the command line, interrupts and tables.
#pragma once

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "cases/app/case_loading.hpp"
#include "cases/app/option_table.hpp"
#include "cases/cli/arguments.hpp"
#include "cases/cli/exit_codes.hpp"
#include "sympathy/continuation/accuracy.hpp"
#include "sympathy/continuation/continuation_options.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy::cli {

// What a journaled run on this machine's threads (basins, sweep) gives Python: the JSON it wrote
// and whether it was interrupted.
struct JournaledOutcome {
  std::string json_path;
  bool interrupted = false;
};

// The command line reads its options into the application layer's requests and runs them there.
using namespace sympathy::app;
using app::load_case;  // beside the overload that reads the command line

// --threads N as given (ShootingOptions::validate checks it: 1 to 256), by default one per core;
// the shooting uses at most as many as it has segments, and its result does not depend on them.
int segment_threads(const Arguments& args);
// The preset --accuracy names (Default without it).
Accuracy accuracy(const Arguments& args);

// The case file of positional 0 with --params and --set.
LoadedCase load_case(const Arguments& args);
// The integrator options --rtol, --atol, --method and --sensitivities on top of `defaults` (for
// orbit and continue: the accuracy preset's); without --linear-solver, defaults.linear_solver (by
// default Automatic: the flow chooses, see LinearSolver).
FlowOptions flow_options(const Arguments& args, FlowOptions defaults);
// A number for a table by a printf format with one double ("%.3f"); "-" where it is not finite
// (a value that was not measured).
std::string table_number(double v, const char* format);
// The same for an orbit's shooting flow (orbit, continue, curve): a --method given turns off the
// presets' switch to BDF where the start is stiff (OrbitOptions::switch_when_stiff), and the
// transient takes the shooting's linear solver.
void shooting_flow_options(const Arguments& args, OrbitOptions& options);

// Installs handlers of SIGINT, SIGTERM and SIGHUP that set the returned flag: a run then stops
// after its current point or output sample and writes complete files of what it has (exit code
// kInterrupted). A second signal ends the program at once (exit code 130).
const std::atomic<bool>* interrupt_flag();

// For commands that write nothing before their end (orbit, fit: one Newton or one optimisation,
// their JSON and CSV written whole at the end): SIGINT, SIGTERM and SIGHUP end the program at
// once with exit code kInterrupted and a line saying so; nothing half-written is left (an equation
// compile under way is stopped and removed first, equation_compiler.hpp). Not for the Python
// module, whose interpreter owns its signals.
void exit_on_interrupt();

}  // namespace sympathy::cli
