// The stand-in for continuation/task_runner_mpi.cpp when sympathy is built without MPI: one
// process, and a clear refusal when started by mpirun anyway.
#include <cstdlib>
#include <stdexcept>

#include "continuation/task_runner_mpi.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy {

bool mpi_built() {
  return false;
}

MpiSession::MpiSession() {
  if (std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMIX_RANK") || std::getenv("PMI_RANK"))
    throw InputError(
        "started by mpirun, but this sympathy was built without MPI (configure with Open MPI "
        "installed: scripts/setup mpi; CMake option SYMPATHY_MPI); every rank would compute the "
        "whole study and write the same files");
}

MpiSession::~MpiSession() = default;

std::vector<bool> MpiSession::all(bool ok) const {
  return {ok};
}

void MpiSession::broadcast(std::string&) const {}

TaskRunSummary run_tasks_mpi(const MpiSession&, std::size_t, const std::vector<bool>&,
                             const std::function<std::optional<TaskRow>(std::size_t)>&,
                             const std::function<void(std::size_t, TaskRow&&)>&,
                             const std::atomic<bool>*) {
  throw std::logic_error("run_tasks_mpi: built without MPI");
}

}  // namespace sympathy
