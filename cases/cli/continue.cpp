// sympathy continue: a branch of periodic orbits in one parameter, with its bifurcations.
#include <cstdio>

#include <algorithm>
#include <memory>
#include <optional>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/equations.hpp"
#include "cases/cli/progress.hpp"
#include "cases/cli/report.hpp"
#include "cases/cli/requests.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/state_describer.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

ContinuationOptions branch_continuation(const Arguments& args, const OdeSystem& system) {
  ContinuationOptions o;
  // A forced system's start: Newton at once unless a transient is asked for (its period is the
  // forcing's; a transient would leave an unstable response for whatever attracts).
  o.orbit.transient = args.number("--transient", system.autonomous() ? o.orbit.transient : 0.0);
  o.orbit.shooting.segments = args.integer("--segments", 1);
  o.initial_step = args.number("--step", o.initial_step);
  o.max_step = args.number("--max-step", o.max_step);
  o.max_points = args.integer("--max-points", o.max_points);
  apply_accuracy(accuracy(args), o);
  shooting_flow_options(args, o.orbit);
  return o;
}

BranchRequest continue_request(const Arguments& args, const LoadedSystem& c) {
  const ParameterWindow window = parameter_window(args, c);
  BranchRequest request;
  request.start_data = c.start_data();
  c.require_orbits();
  if (!c.equations() && !args.has("--start") && !request.start_data)
    throw InputError("--start is required (or --start-data FILE.csv)");
  request.start = args.text("--start", "");
  request.parameter = window.parameter;
  request.from = window.from;
  request.to = window.to;
  request.at = window.at;
  request.initial = args.assignments("--initial");
  request.csv_path = args.text("--csv", "");
  request.switch_at = args.text("--switch-at", "");
  if (!request.switch_at.empty() && !parse_hopf_name(request.switch_at, "--switch-at"))
    parse_event_name(request.switch_at, "--switch-at",
                     {BifurcationType::BranchPoint, BifurcationType::PeriodDoubling},
                     "a branch point or period doubling of the branch, or a Hopf point of the "
                     "equilibria (BP, PD or HB followed by its number, e.g. BP1 or HB1): only "
                     "there is a branch born");
  if (!request.switch_at.empty()) c.require_autonomous("--switch-at (branch switching)");
  if (args.has("--hopf-amplitude")) {
    if (request.switch_at.empty() || !parse_hopf_name(request.switch_at, "--switch-at"))
      throw InputError(
          "--hopf-amplitude: only with --switch-at HBn (the family born at a Hopf point); "
          "expected --switch-at HB1, HB2, ... or no --hopf-amplitude");
    request.hopf_start.amplitude = args.number("--hopf-amplitude", 0.0);
    if (!(request.hopf_start.amplitude > 0.0))
      throw InputError("--hopf-amplitude " + format_number(request.hopf_start.amplitude) +
                       ": expected a positive amplitude (state units)");
  }
  request.parent_path = args.text("--parent", "");
  if (!request.parent_path.empty() && request.switch_at.empty())
    throw InputError("--parent " + request.parent_path +
                     ": expected --switch-at EVENT too (the event of the parent to switch at)");

  if (args.flag("--quiet")) request.progress = nullptr;
  request.verbose = args.flag("--verbose");
  auto& o = request.continuation;
  o = branch_continuation(args, c.system());
  o.orbit.shooting.threads = segment_threads(args);
  o.user_points = args.numbers("--user-points");
  for (double v : o.user_points)
    if (v < std::min(request.from, request.to) || v > std::max(request.from, request.to))
      throw InputError("--user-points " + format_number(v) + ": outside --from " +
                       format_number(request.from) + " .. --to " + format_number(request.to) +
                       "; expected values the branch can reach");
  o.orbit.use_symmetry = !args.flag("--whole-state");
  check_options(o.validate(), "");
  c.check_range(request.parameter, window.ends());
  // The start (fails early with the list of starts).
  c.source(request.start, request.initial, request.start_data);
  const auto json_path = args.value("--json");
  if (json_path) check_writable(*json_path, "--json");
  request.events_path = args.text("--events", "");
  if (!request.csv_path.empty()) check_writable(request.csv_path, "--csv");
  if (!request.events_path.empty()) check_writable(request.events_path, "--events");
  auto inputs = c.inputs();
  inputs.emplace_back("--parent", request.parent_path);
  inputs.emplace_back("--start-data", args.text("--start-data", ""));
  check_distinct_outputs({{"--csv", request.csv_path},
                          {"--events", request.events_path},
                          {"--json", json_path.value_or("")}},
                         inputs);

  return request;
}

int run_continue(const std::vector<std::string>& argv) {
  Arguments args("continue", argv, continue_options(), {"CASE"});
  Stopwatch clock;
  // The case: a metronome case file, or an equation case file (its system compiled or from the
  // cache; its start the file's [states] unless --start names one).
  const LoadedSystem c = load_system(args);
  ProgressLine progress(args.flag("--quiet"));
  BranchRequest request = continue_request(args, c);
  if (request.progress) request.progress = progress.log();
  int points = 0;
  if (progress.enabled())
    request.on_point = [&, own = request.on_point](const ContinuationPoint& p) {
      if (own) own(p);
      progress.position("continue", request.parameter, p.parameter, request.from, request.to,
                        ++points);
    };
  const BranchSource source = c.source(request.start, request.initial, request.start_data);
  const auto json_path = args.value("--json");
  const std::string start_name = request.start_data      ? describe_start_data(*request.start_data)
                                 : request.start.empty() ? "(the file's [states])"
                                                         : request.start;
  std::printf("sympathy continue %s  params %s  start %s  %s from %g to %g\n", c.path().c_str(),
              c.params().empty() ? "(none)" : c.params().c_str(), start_name.c_str(),
              request.parameter.c_str(), request.from, request.to);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const Branch branch = run_branch(source, request, interrupt_flag());
  progress.clear();
  if (!branch.started()) {
    std::printf("  %s\n  run time %.3f s\n", branch.stop_reason.c_str(), clock.seconds());
    return kNumericalFailure;
  }
  const auto& rj = branch.rejected;
  std::printf(
      "  %zu points; stopped: %s\n  steps retried shorter: %d corrector, %d turn, %d "
      "multipliers, %d location\n",
      branch.points.size(), branch.stop_reason.c_str(), rj.corrector, rj.turn, rj.multipliers,
      rj.location);
  if (!branch.origin.empty())
    std::printf("  born at the %s %s\n",
                branch.origin.rfind("HB", 0) == 0 ? "equilibria's" : "parent branch's",
                branch.origin.c_str());
  std::printf("bifurcations:\n");
  print_events(stdout, branch);
  if (request.verbose) print_flow_statistics(stdout, branch.flow);
  // The integrator, where the start's stiffness chose it (the presets).
  const std::string chosen = branch.stiffness
                                 ? "; " + to_string(branch.options.orbit.shooting.flow.method) +
                                       ", " + stiffness_note(*branch.stiffness)
                                 : "";
  std::printf("  run time %.3f s (%ld integrations, %ld steps%s)\n", clock.seconds(),
              branch.flow.calls, branch.flow.steps, chosen.c_str());
  if (json_path) {
    nlohmann::json j = branch_json(branch, request, c.describer());
    j["case"] = c.path();
    j["params_set"] = c.params();
    j["seconds"] = clock.seconds();
    write_json(*json_path, j);
  }
  return exit_code_of(branch);
}

}  // namespace sympathy::cli
