// One branch of periodic orbits from a case's named start, as `continue` and `study` run it:
// the orbit at the first parameter value, then pseudo-arclength continuation one way (or both
// ways from --at), every point streamed to CSV as it is found, events printed as located.
#pragma once

#include <atomic>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"
#include "sympathy/continuation/continuation.hpp"

namespace sympathy::cli {

struct BranchRequest {
  std::string start;
  std::string parameter;
  double from = 0.0, to = 0.0;
  std::optional<double> at;          // start here and go both ways
  std::vector<Assignment> initial;   // state values on top of the start
  std::string csv_path;              // "" for none
  ContinuationOptions continuation;  // bounds are set from from/to
  double transient = 60.0;
  std::FILE* progress = stderr;  // nullptr: quiet
  bool verbose = false;          // multipliers on each progress line
};

struct BranchResult {
  bool started = false;  // the starting orbit converged
  std::string start_failure;
  Branch branch;  // along the branch: the backward part first when two-way
  std::vector<OrbitReport> reports;
  double seconds = 0.0;
};

BranchResult run_branch(const LoadedCase& c, const BranchRequest& request,
                        const std::atomic<bool>* stop);

void print_events(std::FILE* out, const BranchResult& r, const std::string& parameter);
nlohmann::json branch_json(const BranchResult& r, const BranchRequest& request,
                           const MetronomeModel& model);

// Installs a SIGINT handler that sets the returned flag (the run then stops after the current
// point and writes what it has); a second Ctrl-C ends the program at once.
const std::atomic<bool>* interrupt_flag();

}  // namespace sympathy::cli
