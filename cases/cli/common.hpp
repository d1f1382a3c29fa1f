// What every subcommand shares: the application layer's names (the options read into its
// requests: app/arguments.hpp, app/case_arguments.hpp), interrupts and table numbers.
#pragma once

#include <atomic>
#include <string>
#include <utility>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/exit_codes.hpp"
#include "cases/app/option_table.hpp"

namespace sympathy::cli {

// The command line reads its options into the application layer's requests and runs them there.
using namespace sympathy::app;

// A number for a table by a printf format with one double ("%.3f"); "-" where it is not finite
// (a value that was not measured).
std::string table_number(double v, const char* format);

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
