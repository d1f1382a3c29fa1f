// What every subcommand shares: loading a case with its parameter set and --set overrides,
// integrator options from the command line, and timing.
#pragma once

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "cases/cli/arguments.hpp"
#include "cases/cli/exit_codes.hpp"
#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/names.hpp"
#include "sympathy/continuation/accuracy.hpp"
#include "sympathy/continuation/continuation_options.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy::cli {

struct LoadedCase {
  CaseFile file;
  std::string params;  // the parameter set applied ("" if none)
  ModelSpec spec;
};

// Options every command that loads a case accepts.
std::vector<OptionSpec> case_options();
// Integrator options: --rtol, --atol, --method, --sensitivities, --linear-solver.
std::vector<OptionSpec> integrator_options();

// --accuracy (a study or map file's `accuracy`): the engine's presets (accuracy.hpp).
OptionSpec accuracy_option();
// --threads of orbit and continue: the shooting segments integrated side by side.
OptionSpec segment_threads_option();
// --threads N as given (ShootingOptions::validate checks it: 1 to 256), by default one per core;
// the shooting uses at most as many as it has segments, and its result does not depend on them.
int segment_threads(const Arguments& args);
// Throws InputError "WHERE TEXT: expected fast, default or high" unless TEXT names a preset.
Accuracy parse_accuracy(const std::string& text, const std::string& where);
// The preset --accuracy names (Default without it).
Accuracy accuracy(const Arguments& args);

LoadedCase load_case(const Arguments& args);
// InputError naming the case file and its escapement unless the model is differentiable: the
// impulsive escapement (eq. 2) switches discontinuously, and orbits, branches and equilibria
// need the flow's sensitivities (`what`: "orbit", "continue", ...). Before any work.
void require_differentiable(const OdeSystem& system, const std::string& case_path,
                            const std::string& what);
// The same for the file at `path`, parameter set `params` ("" for the file's default) and `sets`.
LoadedCase load_case(const std::string& path, const std::string& params,
                     const std::vector<Assignment>& sets);
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

// Throws the InputError of an options problem (the engine's validate()), named as the command
// line names it ("--step: expected ...", where = "") or as a study file does (where =
// "FILE: branches[2]." gives "FILE: branches[2].step: expected ...").
void check_options(const OptionCheck& problem, const std::string& where);

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

// Throws InputError (prefixed by `where`) unless the model is physically meaningful with
// `parameter` at every one of `values` (ModelSpec::problems: masses and lengths positive,
// damping and stiffness non-negative, ...), so that a range reaching out of the domain is refused
// before any work instead of failing later as an integration error.
void check_parameter_range(const ModelSpec& spec, const std::string& parameter,
                           const std::vector<double>& values, const std::string& where);

// Throws InputError when two of `paths` (option, path) name the same file, or one of them names
// an input (option, path) such as the case file: an output must never replace an input or
// another output of the same run. Files are compared by device and inode, so a hard or symbolic
// link to an input is that input. Empty paths are ignored.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                            const std::vector<std::pair<std::string, std::string>>& inputs);

// `files` with `more` appended (for check_distinct_outputs' lists of inputs).
std::vector<std::pair<std::string, std::string>> with(
    std::vector<std::pair<std::string, std::string>> files,
    std::pair<std::string, std::string> more);

}  // namespace sympathy::cli
