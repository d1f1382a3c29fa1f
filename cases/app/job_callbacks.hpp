// Where a run of jobs side by side is (a map's orbits, a study's branches), for a progress
// display: what a job is doing, a line of the run's log, a job finished. Any may be empty; they
// are called from the jobs' threads (the receiver synchronises).
#pragma once

#include <cstddef>
#include <functional>
#include <string>

namespace sympathy::app {

struct JobCallbacks {
  std::function<void(std::size_t job, const std::string& doing)> job;
  std::function<void(const std::string& line)> log;  // a whole line, with its newline
  std::function<void(std::size_t job)> finished;
};

}  // namespace sympathy::app
