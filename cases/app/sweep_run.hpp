// sympathy sweep as a request, below the command line and Python: one-parameter branches over a
// grid of a second parameter, or one orbit or one fit at each of its values, as independent
// journaled tasks (cases/app/task_run.hpp). The files, in the output directory:
// sweep_journal.csv (a row per task as it finishes), and at the end, in task order whatever the
// threads, sweep_events.csv, sweep_orbits.csv or sweep_fits.csv, and sweep.json.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/study_record.hpp"
#include "cases/app/task_run.hpp"
#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/continuation/task_journal.hpp"

namespace sympathy::app {

struct Sweep {
  std::unique_ptr<LoadedSystem> c;
  // --param: a branch at each value; --data: a fit; neither: an orbit.
  enum class Job { Branches, Orbits, Fits } job = Job::Branches;
  FitRequest fit;  // the fit of every task (--data, --free, --free-initial) ...
  TrajectoryFitOptions fit_options;
  // ... prepared once (the recording read, the names and unknowns checked): each task fits a copy
  // of its problem with the swept value set.
  std::optional<PreparedFit> prepared;
  ParameterWindow window;
  GridAxis over;
  std::vector<double> values;  // of the second parameter, one per task
  BranchRequest request;       // the branch of every task; its parameter values set per task
  std::string start;
  TaskRunOptions run;
  std::string out, journal_path, table_path, json_path;
  std::unique_ptr<TaskJournal> journal;
  StudyRecord record;  // what a resumed journal must have been started with
};

// The sweep `args` asks for, every check made before any work (`ranks`: an MPI job's, for the
// journal's record).
Sweep prepare_sweep(const Arguments& args, int ranks);

// Rank 0's: the output directory and the journal (new, or with `resume` the earlier run's,
// checked to be this sweep's: its record, and each row's value of the second parameter the one
// its task index gives).
void open_sweep_outputs(Sweep& w, bool resume);

// Task index -> its value's row (an orbit, a fit or a branch from the sweep's start with the
// swept parameter at the index's value); nullopt where `stop` interrupted a branch.
std::function<std::optional<TaskRow>(std::size_t)> sweep_tasks(const Sweep& w,
                                                               const std::atomic<bool>* stop);

// Writes the table (events, orbits or fits) and the JSON from the journal's rows.
void write_sweep(const Sweep& w);

// What the sweep's tasks are: "branches", "orbits" or "fits".
std::string sweep_unit(const Sweep& w);

// The sweep on this machine's threads (Python's): prepared, its outputs opened (the journal
// resumed with --resume), the tasks computed (`stop` asked between points), the files written as
// the program writes them; nothing printed.
JournaledOutcome run_sweep_here(
    const Arguments& args, const std::atomic<bool>* stop,
    const std::function<void(std::size_t done, std::size_t total)>& on_recorded = {});

}  // namespace sympathy::app
