// sympathy basins as a request, below the command line and Python: how often each synchronized
// state wins from random starts, over a grid of one or two parameters (cases/basin_study.hpp), as
// journaled tasks (cases/app/task_run.hpp). Files, in the output directory: basins_journal.csv
// (the runs as they finish), and at the end, in task order whatever the threads or ranks,
// basins_runs.csv, basins_shares.csv and basins.json (per grid point, each state's share with its
// 95% Wilson interval).
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/case_loading.hpp"
#include "cases/app/study_record.hpp"
#include "cases/app/task_run.hpp"
#include "sympathy/cases/basin_study.hpp"
#include "sympathy/continuation/task_journal.hpp"
#include "sympathy/continuation/task_runner.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

// Everything a basins run needs, checked before any work.
struct Basins {
  LoadedCase c;
  BasinOptions o;
  TaskRunOptions run;
  std::vector<Assignment> initial;
  std::unique_ptr<BasinStudy> study;
  std::string study_path, title;  // a basins study file's, if the study came from one
  std::string out, journal_path, runs_path, shares_path, json_path;
  StudyRecord record;  // what a resumed journal must have been started with
  std::unique_ptr<TaskJournal> journal;
  std::size_t identity_fields = 0;
};

// The journal's columns after the task index: point, the grid parameters, start, the start
// angles th1_0 ..., then class, t_sync, frequency, phase_th2 ..., amp_th1 ... (and with
// confirm: orbit, orbit_period, orbit_stability, orbit_max_multiplier; with early_stop:
// stopped_at, certified_by).
std::vector<std::string> journal_header(const BasinStudy& study);
// The fields that say which run a row is: point, grid values, start, start angles.
std::vector<std::string> task_fields(const BasinTask& t);
// A run's journal row (the fields after the task index).
std::vector<std::string> row_of(const BasinTask& t, const BasinRun& run, const BasinOptions& o);

// The options and the study `args` asks for (a basins study file, or the command line's), checked;
// no file touched. `ranks`: the MPI job's size (1 without).
Basins prepare_basins(const Arguments& args, int ranks);

// Rank 0's: the output directory and the journal (new, or with `resume` the earlier run's, checked
// to be this study's).
void open_basins_outputs(Basins& b, bool resume);

// Task index -> its run's journal row (nullopt where `stop` interrupted it).
std::function<std::optional<TaskRow>(std::size_t)> basins_tasks(const BasinStudy& study,
                                                                const std::atomic<bool>* stop);

// The final files, in task order, from the journal; returns the shares per grid point (as the
// shares file holds them). Throws OutputError.
std::vector<std::vector<BasinShare>> write_basins(const Basins& b);

// The basins study on this machine's threads (Python's): the request read from `args` and checked,
// the outputs opened (the journal resumed with --resume), the runs computed (`stop` asked between
// them) and the files written as the program writes them, nothing printed.
JournaledOutcome run_basins_here(
    const Arguments& args, const std::atomic<bool>* stop,
    const std::function<void(std::size_t done, std::size_t total)>& on_recorded = {});

}  // namespace sympathy::app
