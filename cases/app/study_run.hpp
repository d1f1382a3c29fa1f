// sympathy study as a request: the branches of one figure from a study file, side by side.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/branch_run.hpp"
#include "cases/app/job_callbacks.hpp"
#include "cases/app/loaded_system.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/study_file.hpp"
#include "cases/app/study_record.hpp"
#include "continuation/task_runner_mpi.hpp"
#include "sympathy/continuation/basin_walk.hpp"
#include "sympathy/continuation/task_journal.hpp"

#include <nlohmann/json.hpp>

namespace sympathy::app {

// sympathy study: the run prepared (the study file read, every branch's and equilibria entry's
// case, start and outputs checked, its request made: what is checked before any work), its
// branches and equilibria computed side by side on run.jobs threads (each as continue or
// equilibria computes it, its CSVs streamed; an entry another starts from before it), a line per
// job to callbacks.log, in the study's order at the end; `stop` asked between points; where each
// running job is to callbacks.job, each one done to callbacks.finished. Jobs are numbered
// branches first, then equilibria entries.
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
  // Per [[equilibria]] entry (study_equilibria_run.cpp): its case, request, result and error.
  std::vector<std::unique_ptr<LoadedSystem>> equilibria_systems;
  std::vector<EquilibriaRequest> equilibria_requests;
  std::vector<EquilibriumBranch> equilibria_results;
  std::vector<std::string> equilibria_errors;
  // The state the equilibria's diagram is drawn in: the study's equilibria_axis, checked against
  // the case, or its first state.
  std::string equilibria_axis;
  // The case as the first entry loaded it (a branch's, else an equilibria entry's).
  const LoadedSystem& first() const {
    return systems.empty() ? *equilibria_systems.front() : *systems.front();
  }
  // The [basins] walk (study_basins_run.cpp): its options checked against the first branch's
  // case, its parameter values, CSV path and result.
  std::optional<BasinWalkOptions> basins_options;
  ParameterValues basins_values;
  std::string basins_csv;
  std::optional<BasinWalk> basins;
  // The walk's journal (OUT/NAME-basins-journal.csv: each run's fate as it finishes, so that a
  // killed walk keeps them), opened before any work; `--resume` reads it and runs only the rest.
  bool resume = false;
  // Under mpirun (the command line's): rank 0 computes the study and writes its files; the
  // others compute the branches again without writing anything and run the walk's runs that rank
  // 0 hands out (study_basins_run.cpp). Null, or one rank: this machine's threads.
  const MpiSession* mpi = nullptr;
  bool writes() const { return !mpi || mpi->rank() == 0; }
  StudyRecord basins_record;  // what the journal may be resumed by (study_record.hpp)
  std::string basins_journal_path;
  std::unique_ptr<TaskJournal> basins_journal;
  std::size_t job_count() const { return study.branches.size() + study.equilibria.size(); }
};
// The study `args` asks for, checked before any work; under `mpi` with more than one rank, only a
// study with [basins] (whose runs the ranks share), and files only on rank 0.
StudyRun study_run(const Arguments& args, const MpiSession* mpi = nullptr);
void run_study_branches(StudyRun& run, const std::atomic<bool>* stop,
                        const JobCallbacks& callbacks = {});
// The study's JSON (run.json_path): per branch its JSON (branch_json) with its name, its CSV's
// file name and its error if any; per equilibria entry as `equilibria --json` writes it
// (equilibria_json), the same three beside; `seconds` the run's time.
void write_study_json(const StudyRun& run, double seconds);

// The [[equilibria]] entries of run.study made requests (study_equilibria_run.cpp): each one's
// case loaded with its `set`, its start, window and outputs checked, before any work; `outputs`
// gains (what, path) of each CSV.
void prepare_study_equilibria(StudyRun& run,
                              std::vector<std::pair<std::string, std::string>>& outputs);
// Entry k computed as `equilibria` computes it (its CSV streamed; switched at the BP of the entry
// it names, already computed); where it is to `doing` (job index `job`).
void run_study_equilibria(StudyRun& run, std::size_t k, const std::atomic<bool>* stop,
                          const std::function<void(const std::string&)>& doing);

// The study's [basins] checked against the first branch's case (its states, start, the walked
// values' range) and made options, before any work; `outputs` gains its CSV and journal. Nothing
// without one.
void prepare_study_basins(StudyRun& run, std::vector<std::pair<std::string, std::string>>& outputs);
// The study's branches that name the walk's attractors: those computed, in the walked parameter.
std::vector<NamedBranch> study_basins_branches(const StudyRun& run);
// The study's [[equilibria]] entries that name the walk's attractors at rest: those computed.
std::vector<NamedEquilibria> study_basins_equilibria(const StudyRun& run);
// The walk (after the branches: their orbits name the attractors), its CSV written; `doing` told
// each value as it starts.
void run_study_basins(StudyRun& run, const std::atomic<bool>* stop,
                      const std::function<void(const std::string&)>& doing);
// The walk's journal opened (after check_distinct_outputs): a new one refused where an earlier
// run's is in the way without --resume, a resumed one checked against run.basins_record.
void open_study_basins_journal(StudyRun& run);
// The walk's JSON: the values, each attractor's shares, the attractors at each value, the fates.
nlohmann::json study_basins_json(const StudyRun& run);

}  // namespace sympathy::app
