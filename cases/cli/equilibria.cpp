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

namespace sympathy::cli {

namespace {

std::string eigenvalue_text(std::complex<double> l) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g%+.6gi", l.real(), l.imag());
  return text;
}

// The eigenvalue nearest the imaginary axis: what crosses it at an event.
std::complex<double> critical(const Eigen::VectorXcd& eigenvalues) {
  std::complex<double> best = eigenvalues[0];
  for (const auto& l : eigenvalues)
    if (std::abs(l.real()) < std::abs(best.real())) best = l;
  return best;
}

void print_equilibrium_events(const EquilibriumBranch& branch) {
  if (branch.events.empty()) {
    std::printf("  no bifurcations on this branch\n");
    return;
  }
  std::printf("  %-4s %-20s %-11s %-28s %s\n", "type", branch.parameter_name.c_str(), "uncertainty",
              "critical eigenvalue", "note");
  for (const auto& e : branch.events) {
    std::string note = e.note;
    if (e.hopf) {
      char text[160];
      std::snprintf(text, sizeof text, "omega %.10g, period %.10g, %s", e.hopf->omega,
                    e.hopf->period, describe_criticality(e.hopf->lyapunov).c_str());
      note = text + (note.empty() ? "" : "; " + note);
    }
    std::printf("  %-4s %-20.12g %-11.1e %-28s %s\n",
                (to_string(e.type) + (e.located ? "" : "?")).c_str(), e.parameter, e.uncertainty,
                eigenvalue_text(critical(e.eigenvalues)).c_str(), note.c_str());
  }
}

}  // namespace

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
  print_equilibrium_events(branch);
  std::printf("  run time %.3f s\n", clock.seconds());
  if (!r.json_path.empty()) write_equilibria_json(r, branch, c, clock.seconds());
  return exit_code_of(branch);
}

}  // namespace sympathy::cli
