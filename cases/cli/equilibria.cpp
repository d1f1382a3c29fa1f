// sympathy equilibria: a branch of equilibria in one parameter, with its folds (LP), branch points
// (BP) and Hopf points (HB), for either kind of case file.
#include <cstdio>

#include <algorithm>
#include <memory>
#include <optional>

#include "cases/app/case_arguments.hpp"
#include "cases/app/requests.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"
#include "cases/cli/report.hpp"

namespace sympathy::cli {

int run_equilibria(const std::vector<std::string>& argv) {
  Arguments args("equilibria", argv, equilibria_options(), {"CASE"});
  Stopwatch clock;
  const LoadedSystem c = load_system(args);
  const OdeSystem& system = c.system();
  const EquilibriaRequest r = equilibria_request(args, c);
  const EquilibriumProblem& problem = r.problem;
  const std::string& start_name = r.start;
  const std::string parameter = system.parameter_names()[problem.parameter];
  std::printf("sympathy equilibria %s  params %s  start %s  %s from %g to %g\n", c.path().c_str(),
              c.params().empty() ? "(none)" : c.params().c_str(),
              start_name.empty() ? "(the file's [states])" : start_name.c_str(), parameter.c_str(),
              problem.from, problem.to);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const bool quiet = args.flag("--quiet");
  ProgressLine progress(quiet);
  std::FILE* log = progress.log();
  int points = 0;
  const auto* stop = interrupt_flag();
  EquilibriumCallbacks callbacks;
  callbacks.on_point = [&](const EquilibriumPoint& p) {
    progress.position("equilibria", parameter, p.parameter, problem.from, problem.to, ++points);
    if (!quiet)
      std::fprintf(log, "  [%4d] %s = %-14.9g |x| = %-12.6g %d unstable  ds %.2g (%d it)\n",
                   p.index, parameter.c_str(), p.parameter, p.state.lpNorm<Eigen::Infinity>(),
                   p.unstable, p.step, p.iterations);
  };
  callbacks.on_event = [&](const EquilibriumEvent& e) {
    if (!quiet)
      std::fprintf(log, "  >> %s at %s = %.10g (+- %.1e)\n", to_string(e.type).c_str(),
                   parameter.c_str(), e.parameter, e.uncertainty);
  };
  callbacks.stop_requested = [&] { return stop && stop->load(); };
  const EquilibriumBranch branch = run_equilibria(r, system, callbacks);
  progress.clear();
  if (!branch.started()) {
    std::printf("  %s\n  run time %.3f s\n", branch.stop_reason.c_str(), clock.seconds());
    return 4;
  }
  const auto& first = branch.points.front();
  const auto& last = branch.points.back();
  std::printf("  %zu points; stopped: %s\n", branch.points.size(), branch.stop_reason.c_str());
  std::printf("  from %s = %.10g (%d unstable) to %s = %.10g (%d unstable)\n", parameter.c_str(),
              first.parameter, first.unstable, parameter.c_str(), last.parameter, last.unstable);
  if (!branch.origin.empty()) std::printf("  %s\n", branch.origin.c_str());
  std::printf("bifurcations:\n");
  print_equilibrium_events(stdout, branch);
  std::printf("  run time %.3f s\n", clock.seconds());
  if (!r.json_path.empty()) write_equilibria_json(r, branch, c, clock.seconds());
  return exit_code_of(branch);
}

}  // namespace sympathy::cli
