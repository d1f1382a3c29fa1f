// The command line's options that load a case of either kind and name a parameter window, read
// into the application layer's loaded system (cases/app/loaded_system.hpp).
#pragma once

#include "cases/app/loaded_system.hpp"
#include "cases/cli/arguments.hpp"
#include "cases/cli/common.hpp"

namespace sympathy::cli {

using app::LoadedSystem;
using app::ParameterWindow;

// The case file of positional 0 with --params and --set, and --start-data's recorded period if
// given (its options checked, the recording read before anything is compiled).
LoadedSystem load_system(const Arguments& args);

// --param (required, one of the case's), --from and --to (required, different) and --at (if
// given); InputError naming the option. Their range is LoadedSystem::check_range's.
ParameterWindow parameter_window(const Arguments& args, const LoadedSystem& c);

}  // namespace sympathy::cli
