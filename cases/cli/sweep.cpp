// sympathy sweep: one-parameter branches over a grid of a second parameter, or one orbit or one
// fit (the fit's profile in the swept parameter) at each of its values, as independent tasks
// (cases/app/task_run.hpp: threads, or the ranks of an MPI job; a journal that a resumed run does
// not compute again). The branches are a coarse cross-check of the two-parameter curves (curve,
// map): each branch's located events at its value of the second parameter. Files, in --out DIR:
// sweep_journal.csv (a row per task as it finishes), and at the end, in task order whatever the
// threads, sweep_events.csv (a row per located event), sweep_orbits.csv (a row per orbit) or
// sweep_fits.csv (a row per fit), and sweep.json.
#include <cstdio>
#include <optional>

#include "cases/app/sweep_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"

namespace sympathy::cli {

int run_sweep(const std::vector<std::string>& argv) {
  Arguments args("sweep", argv, sweep_options(), {"CASE"});
  Stopwatch clock;
  const MpiSession mpi;
  std::optional<Sweep> w;
  if (const auto exit = prepare_every_rank(mpi, [&] {
        w.emplace(prepare_sweep(args, mpi.size()));
        if (mpi.rank() == 0) open_sweep_outputs(*w, args.flag("--resume"));
      }))
    return *exit;
  const auto* stop = interrupt_flag();
  const auto work = sweep_tasks(*w, stop);
  if (mpi.size() > 1 && mpi.rank() > 0) {
    run_journaled(mpi, w->values.size(), nullptr, work, w->run, stop);
    return 0;
  }
  const std::size_t to_compute = w->values.size() - w->journal->resumed();
  char job[160];
  if (w->job == Sweep::Job::Orbits)
    std::snprintf(job, sizeof job, "an orbit");
  else if (w->job == Sweep::Job::Fits)
    std::snprintf(job, sizeof job, "a fit to %s", w->fit.data.c_str());
  else
    std::snprintf(job, sizeof job, "%s from %g to %g", w->window.parameter.c_str(), w->window.from,
                  w->window.to);
  std::fprintf(stderr,
               "sympathy sweep %s  params %s  start %s  %s, over %s %g .. %g (%d values)\n  %zu "
               "in the journal, %zu to compute\n",
               w->c->path().c_str(), w->c->params().empty() ? "(none)" : w->c->params().c_str(),
               w->start.empty() ? "(the file's [states])" : w->start.c_str(), job,
               w->over.parameter.c_str(), w->over.from, w->over.to, w->over.count,
               w->journal->resumed(), to_compute);
  ProgressLine line(args.flag("--quiet"));
  const auto summary = run_journaled(
      mpi, w->values.size(), w->journal.get(), work, w->run, stop, [&](std::size_t done) {
        line.count("sweep", done, w->values.size(), sweep_unit(*w), w->journal->resumed());
      });
  line.clear();
  w->journal->close();
  write_sweep(*w);
  std::fprintf(stderr, "  %zu of %zu %s (%zu computed now, on %d %s)%s; run time %.1f s\n",
               w->journal->rows().size(), w->values.size(), sweep_unit(*w).c_str(),
               summary.computed, summary.threads, summary.threads == 1 ? "worker" : "workers",
               summary.interrupted ? ", interrupted: --resume continues" : "", clock.seconds());
  std::printf("wrote %s, %s and %s\n", w->journal_path.c_str(), w->table_path.c_str(),
              w->json_path.c_str());
  return summary.interrupted ? kInterrupted : 0;
}

}  // namespace sympathy::cli
