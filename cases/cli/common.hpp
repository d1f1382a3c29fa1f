// What every subcommand shares: loading a case with its parameter set and --set overrides,
// integrator options from the command line, and timing.
#pragma once

#include <string>
#include <vector>

#include "cases/cli/arguments.hpp"
#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/names.hpp"
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
// Integrator options: --rtol, --atol, --method, --linear-solver.
std::vector<OptionSpec> integrator_options();

LoadedCase load_case(const Arguments& args);
// The integrator options on top of `defaults`; without --linear-solver, defaults.linear_solver
// (by default Automatic: the flow chooses, see LinearSolver).
FlowOptions flow_options(const Arguments& args, FlowOptions defaults);

// Throws the InputError of an options problem (the engine's validate()), named as the command
// line names it ("--step: expected ...", where = "") or as a study file does (where =
// "FILE: branches[2]." gives "FILE: branches[2].step: expected ...").
void check_options(const OptionCheck& problem, const std::string& where);

}  // namespace sympathy::cli
