// sympathy study as a request: the branches of one figure from a study file, side by side.
#pragma once

#include <atomic>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/branch_run.hpp"
#include "cases/app/job_callbacks.hpp"
#include "cases/app/loaded_system.hpp"
#include "cases/app/study_file.hpp"

namespace sympathy::app {

// sympathy study: the run prepared (the study file read, every branch's case, start
// and outputs checked, its request made: what is checked before any work), its branches computed
// side by side on run.jobs threads (each as continue computes it, its CSVs streamed; a line per
// branch to callbacks.log, in the study's order at the end; `stop` asked between points; where
// each running branch is to callbacks.job, each one done to callbacks.finished).
struct StudyRun {
  Study study;
  std::string out, json_path;
  int jobs = 2;
  std::vector<std::unique_ptr<LoadedSystem>> systems;  // per branch
  std::vector<BranchSource> sources;
  std::vector<BranchRequest> requests;
  std::vector<Branch> results;
  std::vector<std::string> errors;  // why a branch has no result ("" where it has)
  // The marked parameter sets' values of the study's parameter: (set, value), checked before
  // any work.
  std::vector<std::pair<std::string, double>> marks;
};
StudyRun study_run(const Arguments& args);
void run_study_branches(StudyRun& run, const std::atomic<bool>* stop,
                        const JobCallbacks& callbacks = {});
// The study's JSON (run.json_path): per branch its JSON (branch_json) with its name, its CSV's
// file name and its error if any; `seconds` the run's time.
void write_study_json(const StudyRun& run, double seconds);

}  // namespace sympathy::app
