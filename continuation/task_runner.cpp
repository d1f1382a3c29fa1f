#include "sympathy/continuation/task_runner.hpp"

#include <algorithm>
#include <stdexcept>

namespace sympathy {

std::uint64_t task_seed(std::uint64_t seed, std::uint64_t index) {
  // Two rounds of splitmix64's mixer: the seed mixed, then the index added and mixed again, so
  // that task i of seed s and task i + 1 of seed s - 1 are not one stream shifted by a step.
  const auto mix = [](std::uint64_t z) {
    z += 0x9e3779b97f4a7c15ULL;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  };
  return mix(mix(seed) + index);
}

OptionCheck TaskRunOptions::validate() const {
  if (threads < 0) return OptionProblem{"threads", "a positive number of threads (0: every core)"};
  return std::nullopt;
}

int TaskRunOptions::resolved_threads(std::size_t tasks) const {
  int n = threads > 0 ? threads : static_cast<int>(std::thread::hardware_concurrency());
  n = std::max(n, 1);
  if (tasks < static_cast<std::size_t>(n)) n = std::max<int>(1, static_cast<int>(tasks));
  return n;
}

namespace detail {

void check_task_run(std::size_t count, const std::vector<bool>& done, const TaskRunOptions& o) {
  if (const auto problem = o.validate()) throw std::invalid_argument(problem->message());
  if (!done.empty() && done.size() != count)
    throw std::invalid_argument("run_tasks: `done` has " + std::to_string(done.size()) +
                                " entries for " + std::to_string(count) + " tasks");
}

}  // namespace detail

}  // namespace sympathy
