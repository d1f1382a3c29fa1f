// sympathy orbit: one periodic orbit from a named start, with its Floquet multipliers.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <numbers>

#include <nlohmann/json.hpp>

#include "cases/app/requests.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/equations.hpp"
#include "cases/cli/report.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

int run_orbit(const std::vector<std::string>& argv) {
  Arguments args("orbit", argv, orbit_options(), {"CASE"});
  exit_on_interrupt();

  if (case_file_kind(args.positional(0)) == "equations") return run_orbit_equations(args);
  Stopwatch clock;
  const LoadedCase c = load_case(args);
  MetronomeModel model(c.spec);
  require_differentiable(model, c.file.path(), "orbit");
  // From a recorded period: in the whole state space (the data need not lie in a start's
  // symmetric subspace).
  const auto recorded = start_data(args, model.state_names(), c.file.path());
  if (!recorded && !args.has("--start"))
    throw InputError("--start NAME is required (or --start-data FILE.csv); expected one of: " +
                     join(c.file.start_names()));
  const StartSpec* start = recorded ? nullptr : &c.file.start(*args.value("--start"));
  const InvariantSubspace subspace =
      start ? c.file.invariant_subspace(*start, model) : InvariantSubspace();
  const Eigen::VectorXd z0 =
      start ? c.file.initial_state(start, args.assignments("--initial")) : recorded->state0;

  const OrbitOptions o = orbit_request(args);
  if (auto path = args.value("--json")) {
    check_writable(*path, "--json");
    check_distinct_outputs({{"--json", *path}}, {{"case file", c.file.path()},
                                                 {"--start-data", args.text("--start-data", "")}});
  }

  const PeriodicOrbit orbit =
      recorded
          ? orbit_from_recorded_period(model, model.default_parameters(), *recorded, subspace, o)
          : find_periodic_orbit(model, model.default_parameters(), z0, subspace, o);
  const double seconds = clock.seconds();
  const MetronomeDescriber describer(model);
  const MetronomeDescriber::Report report = describer.report(orbit);

  const std::string start_name = start ? start->name : describe_start_data(*recorded);
  std::printf("sympathy orbit %s  params %s  start %s\n", c.file.path().c_str(),
              c.params.empty() ? "(none)" : c.params.c_str(), start_name.c_str());
  print_orbit(stdout, model, orbit, report.amplitudes, report.phase_differences, o);
  return finish_orbit_report(model, orbit, describer, args.flag("--verbose"), args.value("--json"),
                             c.file.path(), c.params,
                             start ? start->name : "data " + recorded->path, seconds);
}

}  // namespace sympathy::cli
