// sympathy: periodic orbits, their stability and their bifurcations, for metronomes on a
// platform (and any system in cases/). One executable, one subcommand per job.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/errors.hpp"
#include "cases/app/exit_codes.hpp"
#include "cases/cli/commands.hpp"

namespace {

struct Command {
  const char* name;
  int (*run)(const std::vector<std::string>&);
  const char* what;
};

const Command kCommands[] = {
    {"simulate", sympathy::cli::run_simulate,
     "integrate from a start; time series to CSV, summary of the end state"},
    {"orbit", sympathy::cli::run_orbit,
     "a periodic orbit from a start: period, Floquet multipliers, stability"},
    {"continue", sympathy::cli::run_continue,
     "a branch of orbits in one parameter, with its bifurcations"},
    {"equilibria", sympathy::cli::run_equilibria,
     "a branch of equilibria in one parameter: folds, branch points, Hopf points"},
    {"curve", sympathy::cli::run_curve, "the curve of a branch's bifurcation in two parameters"},
    {"map", sympathy::cli::run_map, "where orbits are stable in two parameters: curves and a grid"},
    {"study", sympathy::cli::run_study, "the branches of a figure (a study file), side by side"},
    {"bench", sympathy::bench::run_bench,
     "error against run time over integrator settings (the accuracy report)"},
    {"fit", sympathy::cli::run_fit, "parameters fitted to a recorded time series (least squares)"},
    {"basins", sympathy::cli::run_basins,
     "shares of the synchronized states from random starts, over a grid"},
    {"sweep", sympathy::cli::run_sweep, "one-parameter branches over a grid of a second parameter"},
};

std::string usage() {
  const int width = sympathy::app::help_width();
  std::string u =
      "usage: sympathy COMMAND ARGUMENTS [options]\n"
      "       sympathy --version | --help\n\ncommands:\n";
  for (const auto& c : kCommands) {
    std::string left = std::string("  ") + c.name;
    left.resize(14, ' ');
    u += left + sympathy::app::wrap(c.what, 14, width) + "\n";
  }
  u += "\n'sympathy COMMAND --help' lists a command's arguments and options.\n";
  return u;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fputs(usage().c_str(), stderr);
    return 2;
  }
  const std::string command = argv[1];
  if (command == "--help" || command == "-h" || command == "help") {
    std::fputs(usage().c_str(), stdout);
    return 0;
  }
  if (command == "--version") {
    std::printf("sympathy %s\n", SYMPATHY_VERSION);
    return 0;
  }
  const Command* chosen = nullptr;
  std::vector<std::string> names;
  for (const auto& c : kCommands) {
    if (command == c.name) chosen = &c;
    names.push_back(c.name);
  }
  if (!chosen) {
    const std::string near = sympathy::app::did_you_mean(command, names);
    std::fprintf(stderr, "sympathy: unknown command '%s'%s\n%s", command.c_str(),
                 near.empty() ? "" : ("; did you mean '" + near + "'?").c_str(), usage().c_str());
    return 2;
  }
  std::vector<std::string> args(argv + 2, argv + argc);
  try {
    return chosen->run(args);
  } catch (const sympathy::app::HelpRequested& help) {
    std::fputs(help.usage.c_str(), stdout);
    return 0;
  } catch (const sympathy::InputError& e) {
    std::fprintf(stderr, "sympathy %s: error: %s\n", command.c_str(), e.what());
    return sympathy::app::kBadInput;
  } catch (const sympathy::OutputError& e) {
    std::fprintf(stderr, "sympathy %s: output failed: %s\n", command.c_str(), e.what());
    return sympathy::app::kOutputFailed;
  } catch (const sympathy::Interrupted& e) {
    std::fprintf(stderr, "sympathy %s: interrupted: %s\n", command.c_str(), e.what());
    return sympathy::app::kInterrupted;
  } catch (const sympathy::IntegrationError& e) {  // NOLINT: reported, not a crash
    std::fprintf(stderr, "sympathy %s: integration failed: %s\n", command.c_str(), e.what());
    return sympathy::app::kIntegrationFailed;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sympathy %s: %s\n", command.c_str(), e.what());
    return sympathy::app::kFailure;
  }
}
