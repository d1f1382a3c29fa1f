// What the options of the commands that the Python module (python/) runs too are read into (their
// table: cases/app/option_table.hpp), with every check of the command line before any work: one
// reading and one validation for the program and the module.
#pragma once

#include <atomic>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/event_name.hpp"
#include "cases/app/study_file.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"
#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/trajectory_fit.hpp"

namespace sympathy::cli {

// sympathy orbit: its --segments, --transient, --accuracy, integrator options and
// --whole-state read into the engine's OrbitOptions, checked by their validate(). `forced`: a
// periodically forced system, whose transient is 0 unless --transient gives one.
OrbitOptions orbit_request(const Arguments& args, bool forced = false);

// What every branch run reads besides its window and start (continue, sweep): --segments, --step,
// --max-step, --max-points and --transient (0 by default for a forced system), with --accuracy
// and the integrator's options, into ContinuationOptions; the caller adds its own and validates.
ContinuationOptions branch_continuation(const Arguments& args, const OdeSystem& system);

// sympathy continue: the request (the window, the start, the continuation
// options, switching, the outputs), checked against the case `c`.
BranchRequest continue_request(const Arguments& args, const LoadedSystem& c);

// sympathy curve: the request (the branch, the event's name, the second parameter,
// the engine's CurveOptions, checked against the case `c`); the branch (computed as continue
// computes it, or read from --parent); and the event's curve (InputError naming --event for an
// event that has no curve).
struct CurveRequest {
  BranchRequest branch;  // its progress off
  EventName event;
  std::string second;
  int second_index = -1;
  CurveOptions options;
  std::string csv_path;  // "" for none
};
CurveRequest curve_request(const Arguments& args, const LoadedSystem& c);
Branch curve_branch(const CurveRequest& r, const LoadedSystem& c, const BranchSource& source,
                    const std::atomic<bool>* stop);
BifurcationCurve follow_curve(const CurveRequest& r, const OdeSystem& system, const Branch& parent,
                              const Bifurcation& event, const CurveCallbacks& callbacks);

// sympathy study: the run prepared (the study file read, every branch's case, start
// and outputs checked, its request made: what is checked before any work), its branches computed
// side by side on run.jobs threads (each as continue computes it, its CSVs streamed; a line per
// branch to `progress` unless nullptr, in the study's order at the end; `stop` asked between
// points; the count of branches done and where each running one is on `line`, unless nullptr).
struct StudyRun {
  Study study;
  std::string out, json_path;
  int jobs = 2;
  std::vector<std::unique_ptr<LoadedSystem>> systems;  // per branch
  std::vector<BranchSource> sources;
  std::vector<BranchRequest> requests;
  std::vector<Branch> results;
  std::vector<std::string> errors;  // why a branch has no result ("" where it has)
};
StudyRun study_run(const Arguments& args);
void run_study_branches(StudyRun& run, const std::atomic<bool>* stop, std::FILE* progress,
                        ProgressLine* line = nullptr);

// sympathy equilibria: the engine's problem and options read from them, checked
// against the case `c` (the problem's and the options' own checks, the range, the outputs).
struct EquilibriaRequest {
  std::string start;  // "" for an equation case file's [states]
  EquilibriumProblem problem;
  EquilibriumOptions options;
  std::string csv_path;  // "" for none
};
EquilibriaRequest equilibria_request(const Arguments& args, const LoadedSystem& c);

// sympathy fit: the case (a metronome case file, or an equation case file
// compiled; behind pointers: the request's start points into it), the request and the engine's
// options read from them, every output checked (before any work).
struct FitSetup {
  std::unique_ptr<LoadedCase> c;               // a metronome case file ...
  std::unique_ptr<LoadedEquations> equations;  // ... or an equation case file
  std::string case_path, params;
  FitRequest request;
  TrajectoryFitOptions options;
  // The fit's model and problem (prepare_fit on the case's kind of model).
  PreparedFit prepare() const;
};
FitSetup fit_setup(const Arguments& args);
// Comma-separated names of a repeatable option (--free d,s --free c), in order; InputError for an
// empty name.
std::vector<std::string> names(const Arguments& args, const std::string& option);

// sympathy simulate: the output times of --t-end and --dt (0, dt, 2 dt, ..., t_end;
// InputError unless 0 < dt <= t_end) and the integrator options on its defaults (BDF, rtol 1e-8,
// atol 1e-10).
std::vector<double> simulation_times(const Arguments& args);
FlowOptions simulation_flow_options(const Arguments& args);

// sympathy sweep on this machine's threads for Python: the request read from `args` and checked,
// the outputs opened (the journal resumed with --resume), the tasks computed (`stop` asked
// between points) and the files written as the program writes them, nothing printed.
JournaledOutcome run_sweep_here(const Arguments& args, const std::atomic<bool>* stop);

}  // namespace sympathy::cli
