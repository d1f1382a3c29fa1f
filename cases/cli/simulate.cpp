// sympathy simulate: a time series from a start, as CSV, with a summary of where it ends.
#include <algorithm>
#include <cstdio>

#include "cases/app/simulation_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"

namespace sympathy::cli {

int run_simulate(const std::vector<std::string>& argv) {
  Arguments args("simulate", argv, simulate_options(), {"CASE"});
  Stopwatch clock;
  SimulationRun run = prepare_simulation(args);
  const auto* stop = interrupt_flag();
  run_simulation(run, [stop] { return stop->load(); });
  const auto& s = run.summary;
  const auto names = run.system->state_names();
  const auto& angles = run.angles;
  const auto& watched = run.watched;
  const bool csv = !run.out_path.empty();
  std::fprintf(stderr, "sympathy simulate %s  params %s  start %s  %s\n", run.case_path.c_str(),
               run.params.empty() ? "(none)" : run.params.c_str(), run.start_name.c_str(),
               run.model_note.c_str());
  std::fprintf(stderr, "  t = 0 .. %g s, output every %g s%s%s\n", run.t_end, run.dt,
               csv ? " -> " : " (no --out: time series not written)", run.out_path.c_str());
  if (!run.note.empty()) std::fprintf(stderr, "  NOTE: %s\n", run.note.c_str());
  if (!run.failure.empty()) std::fprintf(stderr, "  STOPPED: %s\n", run.failure.c_str());
  if (run.interrupted)
    std::fprintf(stderr, "  INTERRUPTED: the time series ends where the signal came\n");
  std::fprintf(stderr, "  over the last %g s:\n", std::min(10.0, 0.5 * run.t_end));
  if (s.frequency > 0.0)
    std::fprintf(stderr, "    frequency %.6g Hz (period %.6g s, %d cycles)\n", s.frequency,
                 1.0 / s.frequency, s.cycles);
  else
    std::fprintf(stderr, "    frequency: fewer than two cycles of %s\n", names[angles[0]].c_str());
  std::fprintf(stderr, "    amplitudes:");
  for (std::size_t k = 0; k < watched.size(); ++k)
    std::fprintf(stderr, " %s %.4g%s", names[watched[k]].c_str(), s.amplitudes[k],
                 run.directions < 0            ? ""
                 : watched[k] < run.directions ? " m"
                                               : " rad");
  std::fprintf(stderr, "\n");
  if (!s.phase_differences.empty()) {
    std::fprintf(stderr, "    phase differences to th1:");
    for (std::size_t k = 0; k < s.phase_differences.size(); ++k)
      std::fprintf(stderr, " %s %+.4f rad", names[angles[k + 1]].c_str(), s.phase_differences[k]);
    std::fprintf(stderr, "\n");
  }
  const auto& st = run.statistics;
  std::fprintf(stderr,
               "  integrator: %s, rtol %g, atol %g; %ld steps, %ld rhs evaluations, %ld "
               "steep-zone band changes, %ld switchings\n",
               to_string(run.flow.method).c_str(), run.flow.rtol, run.flow.atol, st.steps,
               st.rhs_evaluations, st.steep_roots, st.switchings);
  if (args.flag("--verbose")) print_flow_statistics(stderr, st);
  std::fprintf(stderr, "  run time %.3f s\n", clock.seconds());
  if (!run.failure.empty()) return 3;
  return run.interrupted ? kInterrupted : 0;
}

}  // namespace sympathy::cli
