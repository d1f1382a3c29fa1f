// Equation case files (kind = "equations") in the commands: loading one with --params and --set,
// its system compiled or taken from the cache (equation_compiler.hpp), and the orbit command on
// it. simulate, orbit, continue, equilibria, curve and study read them (through LoadedSystem,
// cases/app/loaded_system.hpp); map and fit do not yet (CaseFile refuses them, naming the kind).
#pragma once

#include <string>

#include <optional>

#include "cases/app/equation_loading.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/common.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/equation_compiler.hpp"

namespace sympathy::cli {

// sympathy orbit on an equation case file: the whole state space (no symmetry), amplitudes of
// every state.
int run_orbit_equations(const Arguments& args);

}  // namespace sympathy::cli
