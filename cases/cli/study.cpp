// sympathy study: the branches that make one figure, described in a study file next to a case
// (cases/figures/*.toml), computed side by side; a CSV per branch and one JSON for the figure.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/study_file.hpp"
#include "cases/app/study_run.hpp"
#include "cases/app/task_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"
#include "cases/cli/report.hpp"

namespace sympathy::cli {

int run_study(const std::vector<std::string>& argv) {
  Arguments args("study", argv, study_options(), {"STUDY"});
  Stopwatch clock;
  // Under mpirun (a study with [basins]): rank 0 computes and writes everything, the others
  // compute the branches again, silently, and share the walk's runs (study_basins_run.cpp).
  // Every rank checks the input; a failure on any rank ends every rank before any work.
  const MpiSession mpi;
  std::optional<StudyRun> prepared;
  if (const auto exit = prepare_every_rank(mpi, [&] { prepared.emplace(study_run(args, &mpi)); }))
    return *exit;
  StudyRun& run = *prepared;
  if (!run.writes()) {
    run_study_branches(run, interrupt_flag());
    run_study_basins(run, interrupt_flag(), {});
    return 0;
  }
  const Study& study = run.study;
  const LoadedSystem& first = run.first();
  const auto& results = run.results;
  const auto& errors = run.errors;
  const std::string& json_path = run.json_path;
  std::printf("sympathy study %s: %s\n  case %s  params %s  parameter %s\n", study.path.c_str(),
              study.title.c_str(), first.path().c_str(), first.params().c_str(),
              study.parameter.c_str());
  if (first.equations()) std::printf("  %s\n", first.build_note().c_str());
  std::fflush(stdout);
  ProgressLine line(args.flag("--quiet"));
  line.start_jobs("study", run.job_count(),
                  study.equilibria.empty() ? "branches" : "branches and equilibria");
  JobCallbacks callbacks;
  if (line.enabled())
    callbacks.job = [&](std::size_t i, const std::string& doing) { line.job(i, doing); };
  std::FILE* log = line.enabled() ? line.log() : stdout;
  callbacks.log = [&](const std::string& text) {
    std::fputs(text.c_str(), log);
    std::fflush(log);
  };
  callbacks.finished = [&](std::size_t i) { line.finish(i); };
  run_study_branches(run, interrupt_flag(), callbacks);
  line.clear();
  run_study_basins(run, interrupt_flag(),
                   callbacks.log ? [&](const std::string& doing) { callbacks.log(doing + "\n"); }
                                 : std::function<void(const std::string&)>{});

  bool ok = true;
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    ok = ok && errors[i].empty() && results[i].started();
    std::printf("bifurcations on %s:\n", study.branches[i].name.c_str());
    print_events(stdout, results[i]);
  }
  // Equilibria as `sympathy equilibria` prints them.
  for (std::size_t k = 0; k < study.equilibria.size(); ++k) {
    const EquilibriumBranch& e = run.equilibria_results[k];
    ok = ok && run.equilibria_errors[k].empty() && e.started();
    std::printf("bifurcations on equilibria %s:\n", study.equilibria[k].name.c_str());
    if (!e.origin.empty()) std::printf("  %s\n", e.origin.c_str());
    print_equilibrium_events(stdout, e);
  }
  if (run.basins)
    print_basins_walk(stdout, *run.basins, study.parameter, study_basins_branches(run),
                      study_basins_equilibria(run));
  write_study_json(run, clock.seconds());
  std::printf("  wrote %s, %zu CSV files of points and %zu of events; run time %.2f s\n",
              json_path.c_str(), study.branches.size() + study.equilibria.size(),
              study.branches.size(), clock.seconds());
  int code = ok ? kDone : kNumericalFailure;
  for (const Branch& b : results) code = worse(code, exit_code_of(b));
  for (const EquilibriumBranch& e : run.equilibria_results) code = worse(code, exit_code_of(e));
  if (run.basins && run.basins->interrupted) code = worse(code, kInterrupted);
  return code;
}

}  // namespace sympathy::cli
