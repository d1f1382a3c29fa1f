// What the commands that run many independent numbered tasks share (sympathy basins, sympathy
// sweep): a parameter grid from the command line, the start of an MPI job (every rank checks the
// input before any work), and the run itself, on one machine's threads or across the ranks of an
// MPI job (continuation/task_runner_mpi.hpp), every result streamed to a journal that a resumed
// run does not compute again (continuation/task_journal.hpp).
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>

#include "continuation/task_runner_mpi.hpp"
#include "sympathy/cases/basin_study.hpp"
#include "sympathy/continuation/task_journal.hpp"
#include "sympathy/continuation/task_runner.hpp"

namespace sympathy::app {

// "NAME=FROM:TO:COUNT" (COUNT values from FROM to TO) or "NAME=VALUE"; InputError naming
// `option`.
GridAxis parse_grid(const std::string& text, const std::string& option);

// Every rank of `mpi` runs `prepare` (the input checked; rank 0 also opens its outputs). A
// failure on any rank ends every rank before any work, reported once, by rank 0 (which rethrows
// it, or says which rank failed): nullopt where the run goes on, else the exit code this rank
// returns at once without a word.
std::optional<int> prepare_every_rank(const MpiSession& mpi, const std::function<void()>& prepare);

// The tasks [0, count) not yet in `journal`, on `run`'s threads, or with an MPI job of more than
// one rank on its workers (rank 0 hands them out); each result appended to `journal` as it comes.
// On an MPI job's workers `journal` is null: they only compute. The summary of the run (on a
// worker: of its own tasks). `on_recorded` hears how many are in the journal after each.
TaskRunSummary run_journaled(const MpiSession& mpi, std::size_t count, TaskJournal* journal,
                             const std::function<std::optional<TaskRow>(std::size_t)>& work,
                             const TaskRunOptions& run, const std::atomic<bool>* stop,
                             const std::function<void(std::size_t)>& on_recorded = {});

// What a journaled run on this machine's threads (basins, sweep) gives Python: the JSON it wrote
// and whether it was interrupted.
struct JournaledOutcome {
  std::string json_path;
  bool interrupted = false;
};

}  // namespace sympathy::app
