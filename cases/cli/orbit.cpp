// sympathy orbit: one periodic orbit from a named start, with its Floquet multipliers.
#include <cstdio>

#include "cases/app/orbit_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"

namespace sympathy::cli {

int run_orbit(const std::vector<std::string>& argv) {
  Arguments args("orbit", argv, orbit_options(), {"CASE"});
  exit_on_interrupt();
  const OrbitRun run = app::run_orbit(args);
  const LoadedSystem& c = *run.c;
  std::printf("sympathy orbit %s  params %s  start %s\n", c.path().c_str(),
              c.params().empty() ? "(none)" : c.params().c_str(), run.start_name.c_str());
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  print_orbit(stdout, c.system(), run.orbit, run.amplitudes, run.phase_differences, run.options,
              run.rms);
  if (args.flag("--verbose")) print_newton_and_flow(stdout, run.orbit);
  std::printf("  run time     %.3f s\n", run.seconds);
  return run.orbit.converged() ? kDone : kNumericalFailure;
}

}  // namespace sympathy::cli
