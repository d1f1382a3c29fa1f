#include "cases/cli/equations.hpp"

#include <cstdio>

#include <nlohmann/json.hpp>

#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"
#include "cases/cli/requests.hpp"
#include "cases/cli/start_data.hpp"
#include "sympathy/cases/state_describer.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

namespace {

// The file's parameter values and its system (compiled or from the cache), `recorded` checked
// already: everything is checked before the compiler runs; a compiler failure is not the user's
// input (a missing compiler or headers, or a bug of the generator) and says so.
LoadedEquations build_loaded(EquationCase file, const std::string& params,
                             const std::vector<Assignment>& sets,
                             std::optional<RecordedPeriod> recorded) {
  const std::string set = params.empty() ? file.default_parameter_set() : params;
  ParameterValues values = file.parameter_values(set, sets);
  EquationBuild build = build_equation_system(file, values);
  return {std::move(file), set, std::move(values), std::move(build), std::move(recorded)};
}

}  // namespace

LoadedEquations load_equations(const Arguments& args) {
  EquationCase file = EquationCase::load(args.positional(0));
  file.parameter_values(args.text("--params", file.default_parameter_set()),
                        args.assignments("--set"));  // the values' errors first
  std::vector<int> angles;  // as the compiled system will declare them (angle_states)
  for (std::size_t i = 0; i < file.system().states.size(); ++i)
    if (file.system().states[i].angle) angles.push_back(static_cast<int>(i));
  std::optional<RecordedPeriod> recorded =
      start_data(args, file.state_names(), file.path(), angles);
  return build_loaded(std::move(file), args.text("--params", ""), args.assignments("--set"),
                      std::move(recorded));
}

LoadedEquations load_equations(const std::string& path, const std::string& params,
                               const std::vector<Assignment>& sets) {
  return build_loaded(EquationCase::load(path), params, sets, std::nullopt);
}

void check_period_known(const LoadedEquations& e) {
  if (!e.build.system->autonomous() && !e.file.system().forcing_period && e.file.plugin().empty())
    throw InputError(e.file.path() +
                     ": its equations use t (a periodically forced system) and it declares no "
                     "forcing period; expected forcing_period = \"EXPRESSION\" (the forcing's "
                     "period from the parameters, e.g. \"2*pi/beta\") at the top of the file");
  if (!e.build.system->autonomous() && !(e.build.system->forcing_period(e.values.data()) > 0.0))
    throw InputError(e.file.path() + ": a periodically forced system whose forcing_period is " +
                     format_number(e.build.system->forcing_period(e.values.data())) +
                     " at these parameter values; expected a positive period");
}

void check_autonomous(const LoadedEquations& e, const std::string& what) {
  if (!e.build.system->autonomous())
    throw InputError(e.file.path() + ": its equations use t (a periodically forced system); " +
                     what +
                     " is for autonomous systems (a forced system's orbits: orbit, "
                     "continue and study)");
}

std::string describe_build(const EquationBuild& build) {
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.2f", build.seconds);
  const std::string what = build.plugin.empty() ? "system" : "plug-in " + build.plugin;
  std::string s = build.compiled ? what + " compiled in " + std::string(seconds) +
                                       " s against the headers in " + build.include_dir
                                 : what + " from the cache";
  // A plug-in is code: say so each time it runs.
  if (!build.plugin.empty())
    s += " (a plug-in is C++ code, run as it is: use only plug-ins you trust)";
  s += " (" + build.library + ")";
  if (!build.rebuilt_because.empty()) s += "; the entry was rebuilt: " + build.rebuilt_because;
  return s;
}

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
