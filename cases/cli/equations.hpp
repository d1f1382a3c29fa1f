// Equation case files (kind = "equations") in the commands: loading one with --params and --set,
// its system compiled or taken from the cache (equation_compiler.hpp), and the orbit command on
// it. simulate, orbit, continue, equilibria, curve and study read them (through LoadedSystem,
// loaded_system.hpp); map and fit do not yet (CaseFile refuses them, naming the kind).
#pragma once

#include <string>

#include <optional>

#include "cases/cli/arguments.hpp"
#include "cases/cli/start_data.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/equation_compiler.hpp"

namespace sympathy::cli {

struct LoadedEquations {
  EquationCase file;
  std::string params;  // the parameter set applied ("" if none)
  ParameterValues values;
  EquationBuild build;
  std::optional<RecordedPeriod> start_data;  // --start-data, if given (orbit, continue)
};

// The file of positional 0, the parameter values of --params and --set, the recorded period of
// --start-data (checked against the file's states before anything is compiled), and its system.
LoadedEquations load_equations(const Arguments& args);
// The same for the file at `path`, parameter set `params` ("" for the file's default) and `sets`.
LoadedEquations load_equations(const std::string& path, const std::string& params,
                               const std::vector<Assignment>& sets);

// InputError unless the file's orbits have a known period: an autonomous system, or a forced one
// (its equations use t) that declares forcing_period (positive at its values).
void check_period_known(const LoadedEquations& e);
// InputError for a forced system: `what` (a command or option) is for autonomous systems only.
void check_autonomous(const LoadedEquations& e, const std::string& what);

// "system compiled in 1.23 s against the headers in DIR (CACHE/KEY.so)" or "system from the
// cache (CACHE/KEY.so)", with why an entry present was rebuilt.
std::string describe_build(const EquationBuild& build);

// sympathy orbit on an equation case file: the whole state space (no symmetry), amplitudes of
// every state.
int run_orbit_equations(const Arguments& args);

}  // namespace sympathy::cli
