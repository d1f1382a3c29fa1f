// The task runner across processes: the same numbered tasks (task_runner.hpp) spread over the
// ranks of an MPI job (`mpirun -np N sympathy basins ...`), manager and workers.
//
// Rank 0 is the manager: it holds the journal and writes every file; it hands out one task index
// at a time to whichever worker (ranks 1 .. N-1) reports back, so that slow simulations do not
// hold up the others (dynamic load balancing), and passes each result to `record`. A worker runs
// one task at a time and sends back its result row. A result depends on its task's index alone,
// so the files equal those of a run on threads. The manager waits for messages by probing every
// millisecond and sleeping in between, not in a blocking receive (Open MPI's blocking receive
// spins, which would take a core from the workers): start N = cores + 1 ranks.
//
// Not part of the installed package: the command line's, built with Open MPI (Debian's
// libopenmpi-dev) when CMake finds it (SYMPATHY_MPI), else with a stand-in that runs one process
// and refuses to run under mpirun (each rank would compute the whole study and write the same
// files).
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sympathy/continuation/task_runner.hpp"

namespace sympathy {

// Whether this program was built with MPI.
bool mpi_built();

// MPI for the lifetime of the object, when the process was started by mpirun (Open MPI's, or
// another PMI launcher's, environment); otherwise a session of one process. Throws InputError
// when started by mpirun and not built with MPI.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // Every rank's `ok` (collective: every rank calls it), so that a failure before any work ends
  // every rank instead of leaving the others waiting.
  std::vector<bool> all(bool ok) const;
  // Rank 0's `text` on every rank (collective: every rank calls it; a session of one process
  // leaves it as it is).
  void broadcast(std::string& text) const;

 private:
  bool initialized_ = false;
  int rank_ = 0;
  int size_ = 1;
};

using TaskRow = std::vector<std::string>;

// Manager and workers over MPI_COMM_WORLD (size >= 2; every rank calls it with the same count).
// On rank 0 runs nothing itself: hands tasks with !done[index] out and calls record(index, row)
// for each result, in the order they come; stops handing out when `stop` is set (an interrupted
// task's worker sends no row) or a worker fails (its exception's message rethrown here as
// std::runtime_error once every worker has stopped). On the workers, runs `work` on the tasks it
// is given; returns a summary of its own tasks. Rows must not contain the character 0x1f.
TaskRunSummary run_tasks_mpi(const MpiSession& session, std::size_t count,
                             const std::vector<bool>& done,
                             const std::function<std::optional<TaskRow>(std::size_t)>& work,
                             const std::function<void(std::size_t, TaskRow&&)>& record,
                             const std::atomic<bool>* stop = nullptr);

}  // namespace sympathy
