#include "cases/cli/equations.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "cases/app/requests.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"
#include "sympathy/cases/state_describer.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

int run_orbit_equations(const Arguments& args) {
  Stopwatch clock;
  if (args.flag("--whole-state"))
    throw InputError(
        "--whole-state: only for a metronome case file (an equation case file's "
        "orbits are always computed in the whole state space)");
  const LoadedEquations e = load_equations(args);
  const OdeSystem& system = *e.build.system;
  const auto& recorded = e.start_data;
  check_start_data_system(recorded, system, e.file.path());
  check_period_known(e);
  const StartSpec* start = args.has("--start") ? &e.file.start(*args.value("--start")) : nullptr;
  const Eigen::VectorXd z0 =
      recorded ? recorded->state0 : e.file.initial_state(start, args.assignments("--initial"));

  const OrbitOptions o = orbit_request(args, !system.autonomous());
  if (auto path = args.value("--json")) {
    check_writable(*path, "--json");
    check_distinct_outputs({{"--json", *path}}, {{"case file", e.file.path()},
                                                 {"plug-in source", e.file.plugin()},
                                                 {"--start-data", args.text("--start-data", "")}});
  }

  const PeriodicOrbit orbit =
      recorded ? orbit_from_recorded_period(system, e.values, *recorded, InvariantSubspace(), o)
               : find_periodic_orbit(system, e.values, z0, InvariantSubspace(), o);
  const double seconds = clock.seconds();
  const StateDescriber describer(system);
  const StateDescriber::Sizes sizes = describer.sizes(orbit);

  const std::string start_name = recorded ? describe_start_data(*recorded)
                                 : start  ? start->name
                                          : "(the file's [states])";
  std::printf("sympathy orbit %s  params %s  start %s\n", e.file.path().c_str(),
              e.params.empty() ? "(none)" : e.params.c_str(), start_name.c_str());
  std::printf("  %s\n", describe_build(e.build).c_str());
  print_orbit(stdout, system, orbit, sizes.amplitudes, {}, o, sizes.rms);
  return finish_orbit_report(system, orbit, describer, args.flag("--verbose"), args.value("--json"),
                             e.file.path(), e.params,
                             recorded ? "data " + recorded->path
                             : start  ? start->name
                                      : "",
                             seconds);
}

}  // namespace sympathy::cli
