#include "cases/app/task_run.hpp"

#include <cmath>
#include <exception>
#include <vector>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

GridAxis parse_grid(const std::string& text, const std::string& option) {
  const auto fail = [&] {
    return InputError(
        option + " " + text +
        ": expected NAME=FROM:TO:COUNT (e.g. k=40:90:6), or NAME=VALUE for one value");
  };
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw fail();
  GridAxis a;
  a.parameter = text.substr(0, eq);
  std::vector<std::string> parts;
  std::size_t from = eq + 1;
  for (std::size_t colon; (colon = text.find(':', from)) != std::string::npos; from = colon + 1)
    parts.push_back(text.substr(from, colon - from));
  parts.push_back(text.substr(from));
  const auto number = [&](const std::string& s) {
    const auto v = finite_number(s);
    if (!v) throw fail();
    return *v;
  };
  if (parts.size() == 1) {
    a.from = a.to = number(parts[0]);
    a.count = 1;
    return a;
  }
  if (parts.size() != 3) throw fail();
  a.from = number(parts[0]);
  a.to = number(parts[1]);
  const double count = number(parts[2]);
  if (count != std::floor(count) || count < 0 || count > 1e6) throw fail();
  a.count = static_cast<int>(count);
  return a;
}

std::optional<int> prepare_every_rank(const MpiSession& mpi, const std::function<void()>& prepare) {
  std::exception_ptr failure;
  try {
    prepare();
  } catch (...) {
    failure = std::current_exception();
  }
  if (mpi.size() <= 1) {
    if (failure) std::rethrow_exception(failure);
    return std::nullopt;
  }
  const auto ok = mpi.all(!failure);
  if (failure && (mpi.rank() == 0 || ok[0])) std::rethrow_exception(failure);
  // Rank 0 reports the same error and gives the job its exit code (a worker exiting non-zero
  // first would make mpirun end rank 0 before it prints).
  if (failure) return 0;
  for (int r = 1; r < mpi.size(); ++r)
    if (!ok[r]) {
      if (mpi.rank() == 0)
        throw InputError("rank " + std::to_string(r) + " failed before any work (above)");
      return 2;
    }
  return std::nullopt;
}

TaskRunSummary run_journaled(const MpiSession& mpi, std::size_t count, TaskJournal* journal,
                             const std::function<std::optional<TaskRow>(std::size_t)>& work,
                             const TaskRunOptions& run, const std::atomic<bool>* stop,
                             const std::function<void(std::size_t)>& on_recorded) {
  if (mpi.size() > 1 && mpi.rank() > 0) return run_tasks_mpi(mpi, count, {}, work, {}, stop);
  std::size_t recorded = journal->resumed();
  const auto record = [&](std::size_t index, TaskRow&& row) {
    journal->append(index, std::move(row));
    if (on_recorded) on_recorded(++recorded);
  };
  return mpi.size() > 1 ? run_tasks_mpi(mpi, count, journal->done(), work, record, stop)
                        : run_tasks<TaskRow>(count, journal->done(), work, record, run, stop);
}

}  // namespace sympathy::app
