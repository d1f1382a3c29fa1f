// sympathy basins: how often each synchronized state wins from random starts, over a grid of one
// or two parameters (cases/basin_study.hpp), run on every core (continuation/task_runner.hpp),
// every finished run streamed to a journal that a resumed run does not compute again
// (continuation/task_journal.hpp). Files, in --out DIR: basins_journal.csv (the runs as they
// finish), and at the end, in task order whatever the threads, basins_runs.csv, basins_shares.csv
// and basins.json (per grid point, each state's share with its 95% Wilson interval; written by
// the application layer, app/basins_run). Under mpirun the same across the ranks of an MPI job
// (continuation/task_runner_mpi.hpp), with the same files.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cases/app/basins_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"

namespace sympathy::cli {

int run_basins(const std::vector<std::string>& argv) {
  Arguments args("basins", argv, basins_options(), {"CASE|STUDY.toml"});
  Stopwatch clock;
  // Under mpirun: rank 0 manages (journal, files, messages), the others simulate. Every rank
  // checks the input; a failure on any rank ends every rank before any work, reported once.
  const MpiSession mpi;
  const bool distributed = mpi.size() > 1;
  std::optional<Basins> b;
  if (const auto exit = prepare_every_rank(mpi, [&] {
        b.emplace(prepare_basins(args, mpi.size()));
        if (mpi.rank() == 0) open_basins_outputs(*b, args.flag("--resume"));
      }))
    return *exit;
  const BasinStudy& study = *b->study;
  const auto* stop = interrupt_flag();
  const auto work = basins_tasks(study, stop);
  if (distributed && mpi.rank() > 0) {
    run_journaled(mpi, study.tasks(), nullptr, work, b->run, stop);
    return 0;
  }

  TaskJournal& journal = *b->journal;
  const std::size_t to_compute = study.tasks() - journal.resumed();
  const int workers = distributed ? mpi.size() - 1 : b->run.resolved_threads(to_compute);
  if (!b->study_path.empty())
    std::fprintf(stderr, "sympathy basins %s: %s\n", b->study_path.c_str(), b->title.c_str());
  std::fprintf(stderr, "%s%s  params %s  escapement %s\n",
               b->study_path.empty() ? "sympathy basins " : "  case ", b->c.file.path().c_str(),
               b->c.params.empty() ? "(none)" : b->c.params.c_str(),
               to_string(b->c.spec.escapement).c_str());
  std::string grid_text;
  for (const auto& a : b->o.grid)
    grid_text += "  " + a.parameter + " " + format_number(a.from) + " .. " + format_number(a.to) +
                 " (" + std::to_string(a.count) + (a.count == 1 ? " value)" : " values)");
  std::fprintf(stderr,
               "  grid%s; %d starts a point, angles in [%g, %g] rad, seed %llu; %g s each\n",
               grid_text.c_str(), b->o.starts, b->o.angle_min, b->o.angle_max,
               static_cast<unsigned long long>(b->o.seed), b->o.t_end);
  std::fprintf(stderr, "  %zu runs: %zu in the journal, %zu to compute on %d %s%s\n", study.tasks(),
               journal.resumed(), to_compute, workers, distributed ? "MPI worker" : "thread",
               workers == 1 ? "" : "s");

  ProgressLine line(args.flag("--quiet"));
  const auto summary =
      run_journaled(mpi, study.tasks(), &journal, work, b->run, stop, [&](std::size_t done) {
        line.count("basins", done, study.tasks(), "runs", journal.resumed());
      });
  line.clear();
  journal.close();
  const auto shares = write_basins(*b);
  for (std::size_t p = 0; p < study.points(); ++p) {
    const auto values = study.values(p);
    std::string at;
    for (std::size_t a = 0; a < values.size(); ++a)
      at += (a ? ", " : "") + b->o.grid[a].parameter + " = " + format_number(values[a]);
    const std::size_t runs = shares[p].empty() ? 0 : shares[p].front().proportion.trials;
    std::fprintf(stderr, "  %s (%zu runs):", at.c_str(), runs);
    for (const auto& s : shares[p])
      if (s.proportion.count > 0)
        std::fprintf(stderr, "  %s %.3f [%.3f, %.3f]", s.state.c_str(), s.proportion.share,
                     s.proportion.lower, s.proportion.upper);
    std::fprintf(stderr, "\n");
  }
  if (summary.interrupted)
    std::fprintf(stderr, "  INTERRUPTED: %zu of %zu runs done; --resume continues the journal\n",
                 journal.rows().size(), study.tasks());
  std::fprintf(stderr,
               "  wrote %s, %s, %s (journal %s); %zu runs computed in %.2f s, run time %.2f s\n",
               b->runs_path.c_str(), b->shares_path.c_str(), b->json_path.c_str(),
               b->journal_path.c_str(), summary.computed, summary.seconds, clock.seconds());
  return summary.interrupted ? kInterrupted : 0;
}

}  // namespace sympathy::cli
