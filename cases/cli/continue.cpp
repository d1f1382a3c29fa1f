// sympathy continue: a branch of periodic orbits in one parameter, with its bifurcations.
#include <cstdio>

#include <algorithm>
#include <memory>
#include <optional>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"
#include "cases/cli/report.hpp"

namespace sympathy::cli {

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
                                 : request.hopf_point    ? "the Hopf " + request.hopf_point_name
                                 : c.saved_orbit()       ? source.start_name
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
    write_branch_json(*json_path, branch, request, c, clock.seconds());
  }
  return exit_code_of(branch);
}

}  // namespace sympathy::cli
