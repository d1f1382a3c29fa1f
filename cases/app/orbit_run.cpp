#include "cases/app/orbit_run.hpp"

#include "cases/app/case_arguments.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/start_data.hpp"
#include "sympathy/cases/metronome_describer.hpp"
#include "sympathy/cases/state_describer.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/symmetry_reduction.hpp"
#include "sympathy/core/output_file.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

OrbitRun run_orbit(const Arguments& args) {
  const Stopwatch clock;
  OrbitRun run;
  run.c = std::make_unique<LoadedSystem>(load_system(args));
  const LoadedSystem& c = *run.c;
  c.require_orbits();
  const OdeSystem& system = c.system();
  const MetronomeModel* metronomes = c.metronome_model();
  if (!metronomes && args.flag("--whole-state"))
    throw InputError(
        "--whole-state: only for a metronome case file (an equation case file's "
        "orbits are always computed in the whole state space)");
  const auto& recorded = c.start_data();
  const auto& saved = c.saved_orbit();
  if (metronomes && !recorded && !saved && !args.has("--start"))
    throw InputError(
        "--start NAME is required (or --start-data FILE.csv, or --parent FILE --from-point "
        "POINT); expected one of: " +
        join(c.start_names()));
  // From a recorded period: Newton at once in the whole state space (the data need not lie in a
  // start's symmetric subspace); a forced system's transient 0 unless --transient gives one.
  const BranchSource source =
      c.source(args.text("--start", ""), args.assignments("--initial"), recorded);
  run.options = orbit_request(args, !system.autonomous());
  const auto guess = period_guess(args);
  if (saved && !args.has("--segments")) run.options.shooting.segments = saved->segments;
  if (const auto path = args.value("--json")) {
    check_writable(*path, "--json");
    check_distinct_outputs({{"--json", *path}}, c.inputs());
  }

  // A saved orbit: Newton from it at once (it may be unstable: no transient).
  run.orbit = recorded ? orbit_from_recorded_period(system, source.values, *recorded,
                                                    source.subspace, run.options)
              : saved  ? solve_periodic_orbit(system, source.values, source.start_state,
                                              saved->period, source.subspace, run.options)
              : guess  ? solve_periodic_orbit(system, source.values, source.start_state, *guess,
                                              source.subspace, run.options)
                       : find_periodic_orbit(system, source.values, source.start_state,
                                             source.subspace, run.options);
  // A recording over [0, 1] that does not start its orbit may be AUTO's dat, its time scaled.
  if (recorded && !run.orbit.converged() && !(recorded->scaled_by > 0.0) &&
      recorded->start_time == 0.0 && recorded->span == 1.0)
    run.orbit.newton.reason +=
        "; the recording's time runs from 0 to 1: if it is scaled to one period (AUTO's dat "
        "files), give the period with --data-period";
  run.seconds = clock.seconds();
  if (metronomes) {
    const MetronomeDescriber::Report report = MetronomeDescriber(*metronomes).report(run.orbit);
    run.amplitudes = report.amplitudes;
    run.phase_differences = report.phase_differences;
  } else {
    const StateDescriber::Sizes sizes = StateDescriber(system).sizes(run.orbit);
    run.amplitudes = sizes.amplitudes;
    run.rms = sizes.rms;
  }
  run.start_name = recorded              ? describe_start_data(*recorded)
                   : saved               ? source.start_name
                   : args.has("--start") ? *args.value("--start")
                                         : "(the file's [states])";
  run.json = orbit_json(system, run.orbit, &c.describer());
  run.json["case"] = c.path();
  run.json["params_set"] = c.params();
  run.json["start"] = recorded ? "data " + recorded->path
                      : saved  ? source.start_name
                               : args.text("--start", "");
  run.json["seconds"] = run.seconds;
  if (const auto path = args.value("--json")) write_file_atomically(*path, run.json.dump(2) + "\n");
  return run;
}

IntegrationAsRun integration_as_run(const OdeSystem& model, const PeriodicOrbit& orbit,
                                    const OrbitOptions& options) {
  IntegrationAsRun run;
  run.flow = orbit.stiffness ? after_stiffness(options.shooting.flow, *orbit.stiffness)
                             : options.shooting.flow;
  // The system integrated: the reduction's where a symmetry reduced the computation.
  const auto reduction = orbit.reduction.empty()
                             ? std::nullopt
                             : symmetry_reduction(model, orbit.parameters, orbit.subspace);
  const OdeSystem& integrated =
      reduction ? *reduction->system : static_cast<const OdeSystem&>(model);
  run.integrated_dimension = integrated.dimension();
  if (run.flow.method == Method::ERK)
    run.solver.append(" ").append(to_string(run.flow.explicit_table));
  else if (run.flow.nonlinear_solver == NonlinearSolver::Newton)
    run.solver.append(" (")
        .append(to_string(resolved_linear_solver(integrated, run.flow)))
        .append(" linear solver)");
  return run;
}

}  // namespace sympathy::app
