// The files of `sympathy basins` (cases/cli/basins.cpp): the journal's columns and rows, and at
// the end the runs, the shares and the JSON, written whole in task order from the journal, so
// that they do not depend on the threads or ranks that computed the runs.
#pragma once

#include <atomic>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cases/app/study_record.hpp"
#include "cases/cli/common.hpp"
#include "sympathy/cases/basin_study.hpp"
#include "sympathy/continuation/task_journal.hpp"
#include "sympathy/continuation/task_runner.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::cli {

// Everything a basins run needs, checked before any work.
struct Basins {
  LoadedCase c;
  BasinOptions o;
  TaskRunOptions run;
  std::vector<Assignment> initial;
  std::unique_ptr<BasinStudy> study;
  std::string study_path, title;  // a basins study file's, if the study came from one
  std::string out, journal_path, runs_path, shares_path, json_path;
  StudyRecord record;  // what a resumed journal must have been started with
  std::unique_ptr<TaskJournal> journal;
  std::size_t identity_fields = 0;
};

// The journal's columns after the task index: point, the grid parameters, start, the start
// angles th1_0 ..., then class, t_sync, frequency, phase_th2 ..., amp_th1 ... (and with
// confirm: orbit, orbit_period, orbit_stability, orbit_max_multiplier).
std::vector<std::string> journal_header(const BasinStudy& study);
// The fields that say which run a row is: point, grid values, start, start angles.
std::vector<std::string> task_fields(const BasinTask& t);
// A run's journal row (the fields after the task index).
std::vector<std::string> row_of(const BasinTask& t, const BasinRun& run, bool confirm);

// The final files, in task order, from the journal; the shares printed on `report` with the
// run time (nullptr: not printed). Throws OutputError.
void write_results(const Basins& b, const TaskRunSummary& summary, const Stopwatch& clock,
                   std::FILE* report = stderr);

// sympathy basins on this machine's threads for Python: the request read from `args` and checked,
// the outputs opened (the journal resumed with --resume), the runs computed (`stop` asked between
// them) and the files written as the program writes them, nothing printed.
JournaledOutcome run_basins_here(const Arguments& args, const std::atomic<bool>* stop);

}  // namespace sympathy::cli
