// The one option table: every command's options (the command line parses them and prints them
// as its help, from which the docs' reference is built; Python's functions take them as
// keywords, typed by their kind). The shared groups first, then each command's.
#pragma once

#include <string>
#include <vector>

#include "cases/app/options.hpp"

namespace sympathy::app {

// Shared groups.
std::vector<OptionSpec> case_options();        // --params, --set
std::vector<OptionSpec> integrator_options();  // --rtol, --atol, --method, --sensitivities, ...
OptionSpec accuracy_option();                  // --accuracy fast|default|high
OptionSpec segment_threads_option();           // --threads (an orbit's segments side by side)
OptionSpec start_data_option();                // --start-data FILE.csv
// What every branch run reads besides its window and start (continue, sweep).
std::vector<OptionSpec> branch_step_options();

// Each command's.
std::vector<OptionSpec> orbit_options();
std::vector<OptionSpec> continue_options();
std::vector<OptionSpec> curve_options();
std::vector<OptionSpec> equilibria_options();
std::vector<OptionSpec> study_options();
std::vector<OptionSpec> fit_options();
std::vector<OptionSpec> simulate_options();
std::vector<OptionSpec> basins_options();
std::vector<OptionSpec> map_options();
std::vector<OptionSpec> sweep_options();
std::vector<OptionSpec> bench_options();

// A command's arguments: its positional ones' names ("CASE") and its options.
struct CommandOptions {
  std::vector<std::string> positional;
  std::vector<OptionSpec> options;
};
// The commands that take options, in the order `sympathy --help` lists them.
std::vector<std::string> commands();
// InputError for a command that is none of them.
CommandOptions command_options(const std::string& command);

}  // namespace sympathy::app
