// sympathy: periodic orbits, their stability and their bifurcations, for metronomes on a
// platform (and any system in cases/). One executable, one subcommand per job.
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include "cases/cli/arguments.hpp"
#include "cases/cli/commands.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/flow.hpp"

namespace {

void print_usage() {
  std::fputs(
      "usage: sympathy COMMAND CASE [options]\n"
      "commands:\n"
      "  simulate   integrate from a start; time series to CSV, summary of the end state\n"
      "  orbit      a periodic orbit from a start: period, Floquet multipliers, stability\n"
      "  continue   a branch of orbits in one parameter, with its bifurcations\n"
      "  equilibria a branch of equilibria in one parameter: folds, branch points, Hopf points\n"
      "  curve      the curve of a branch's bifurcation in two parameters\n"
      "  map        where orbits are stable in two parameters: curves and a grid\n"
      "  study      the branches of a figure (cases/figures/*.toml), side by side\n"
      "  bench      error against run time over integrator settings (the accuracy report)\n"
      "  fit        parameters fitted to a recorded time series (least squares)\n"
      "  basins     shares of the synchronized states from random starts, over a grid\n"
      "  sweep      one-parameter branches over a grid of a second parameter\n"
      "run 'sympathy COMMAND --help' for the options of a command\n",
      stderr);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
    print_usage();
    return argc < 2 ? 2 : 0;
  }
  const std::string command = argv[1];
  std::vector<std::string> args(argv + 2, argv + argc);
  try {
    if (command == "simulate") return sympathy::cli::run_simulate(args);
    if (command == "orbit") return sympathy::cli::run_orbit(args);
    if (command == "continue") return sympathy::cli::run_continue(args);
    if (command == "equilibria") return sympathy::cli::run_equilibria(args);
    if (command == "curve") return sympathy::cli::run_curve(args);
    if (command == "map") return sympathy::cli::run_map(args);
    if (command == "study") return sympathy::cli::run_study(args);
    if (command == "bench") return sympathy::cli::run_bench(args);
    if (command == "fit") return sympathy::cli::run_fit(args);
    if (command == "basins") return sympathy::cli::run_basins(args);
    if (command == "sweep") return sympathy::cli::run_sweep(args);
    std::fprintf(stderr, "sympathy: unknown command '%s'\n", command.c_str());
    print_usage();
    return 2;
  } catch (const sympathy::cli::HelpRequested& help) {
    std::fputs(help.usage.c_str(), stdout);
    return 0;
  } catch (const sympathy::InputError& e) {
    std::fprintf(stderr, "sympathy %s: error: %s\n", command.c_str(), e.what());
    return 2;
  } catch (const sympathy::OutputError& e) {
    std::fprintf(stderr, "sympathy %s: output failed: %s\n", command.c_str(), e.what());
    return 5;
  } catch (const sympathy::Interrupted& e) {
    std::fprintf(stderr, "sympathy %s: interrupted: %s\n", command.c_str(), e.what());
    return 6;
  } catch (const sympathy::IntegrationError& e) {  // NOLINT: reported, not a crash
    std::fprintf(stderr, "sympathy %s: integration failed: %s\n", command.c_str(), e.what());
    return 3;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sympathy %s: %s\n", command.c_str(), e.what());
    return 1;
  }
}
