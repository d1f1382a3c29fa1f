// Many independent jobs (a basin study's simulations, one per grid point and random start) run
// on every core of one machine, with results that do not depend on how they were spread out.
//
// Tasks are numbered 0 .. count-1. Each task computes from its index alone: whatever is random in
// it is drawn from a generator seeded by task_seed(seed, index) (splitmix64, a counter-based
// seed: no generator is shared or carried from one task to the next), so a task gives the same
// bits on any thread, in any order, in a resumed run or on another process. Threads take the
// next task from one atomic counter (dynamic load balancing: simulations differ in length, the
// integrator working hardest through slow transients and near-resonant platforms, so a static
// split would leave threads idle while one finishes its slow share). Results are handed to `record`
// one at a time (under a lock), in the order they finish: a journal streams them; the final files
// are written afterwards, in task order, from what was recorded.
//
// A stop flag (the CLI's interrupt flag: SIGINT, SIGTERM, SIGHUP) is read before each task is
// taken and may be read inside a task (which then returns no result): the run stops after the
// tasks under way, every recorded result whole.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <vector>

#include "sympathy/core/option_check.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

// The seed of task `index` of a run seeded with `seed`: splitmix64 (Steele, Lea, Flood, OOPSLA
// 2014; the mixer behind java.util.SplittableRandom, which xoshiro's authors recommend for seeding)
// of splitmix64(seed) + index, so that neighbouring tasks and neighbouring seeds get unrelated
// streams. Seed a std::mt19937_64 with it.
std::uint64_t task_seed(std::uint64_t seed, std::uint64_t index);

// A uniform double in [0, 1) from 53 bits of a 64-bit generator's output: the same value on every
// standard library (std::uniform_real_distribution's algorithm is left to the implementation).
inline double unit_uniform(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;
}

struct TaskRunOptions {
  int threads = 0;  // worker threads; 0: one per core (std::thread::hardware_concurrency)

  OptionCheck validate() const;
  // The threads a run of `tasks` tasks uses: `threads` (or the cores), at most one per task, at
  // least one.
  int resolved_threads(std::size_t tasks) const;
};

struct TaskRunSummary {
  std::size_t tasks = 0;     // in the run: 0 .. tasks-1
  std::size_t skipped = 0;   // already done before the run (a resumed journal's)
  std::size_t computed = 0;  // results recorded by this run
  int threads = 0;
  bool interrupted = false;  // the stop flag ended the run before every task was done
  double seconds = 0.0;
};

// Runs `work(index)` for every index in [0, count) with !done[index] (done empty: none done), on
// options.resolved_threads threads, and passes each result to `record(index, result)`, one call
// at a time, in the order they finish. `work` returning no result (it saw the stop flag) records
// nothing. An exception from `work` or `record` stops the run (no new task is taken) and is
// rethrown here once every thread has ended. Throws std::invalid_argument for invalid options or
// a `done` of another size than count.
template <class Result>
TaskRunSummary run_tasks(std::size_t count, const std::vector<bool>& done,
                         const std::function<std::optional<Result>(std::size_t)>& work,
                         const std::function<void(std::size_t, Result&&)>& record,
                         const TaskRunOptions& options, const std::atomic<bool>* stop = nullptr);

// ---- implementation

namespace detail {
void check_task_run(std::size_t count, const std::vector<bool>& done, const TaskRunOptions& o);
}

template <class Result>
TaskRunSummary run_tasks(std::size_t count, const std::vector<bool>& done,
                         const std::function<std::optional<Result>(std::size_t)>& work,
                         const std::function<void(std::size_t, Result&&)>& record,
                         const TaskRunOptions& options, const std::atomic<bool>* stop) {
  detail::check_task_run(count, done, options);
  Stopwatch clock;
  TaskRunSummary summary;
  summary.tasks = count;
  for (std::size_t i = 0; i < done.size(); ++i) summary.skipped += done[i] ? 1 : 0;
  summary.threads = options.resolved_threads(count - summary.skipped);

  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex lock;  // guards record, summary.computed, error
  std::exception_ptr error;
  const auto stopped = [&] { return failed.load() || (stop && stop->load()); };
  const auto worker = [&] {
    while (!stopped()) {
      const std::size_t index = next.fetch_add(1);
      if (index >= count) return;
      if (!done.empty() && done[index]) continue;
      try {
        std::optional<Result> result = work(index);
        if (!result) continue;
        std::lock_guard<std::mutex> guard(lock);
        record(index, std::move(*result));
        ++summary.computed;
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (!error) error = std::current_exception();
        failed = true;
      }
    }
  };
  if (summary.threads <= 1) {
    worker();
  } else {
    std::vector<std::jthread> pool;
    for (int t = 0; t < summary.threads; ++t) pool.emplace_back(worker);
  }  // the jthreads join here
  if (error) std::rethrow_exception(error);
  summary.interrupted = summary.skipped + summary.computed < count;
  summary.seconds = clock.seconds();
  return summary;
}

}  // namespace sympathy
