// What the options of orbit, continue, curve, equilibria and simulate are read into (their table:
// cases/app/option_table.hpp), with every check before any work: one reading and one validation
// for the program and the Python module. The other commands' requests are in their own
// *_run.hpp (study_run, fit_run, map_run, sweep_run, basins_run; orbit_run and simulation_run
// build on these).
#pragma once

#include <atomic>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/event_name.hpp"
#include "cases/app/study_file.hpp"
#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/generalized_hopf.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy::app {

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
// A --user-value or --stop-at given as QUANTITY=VALUE (period, max_NAME, min_NAME); InputError
// naming the option and the quantities the system has.
UserValue user_value(const Assignment& a, bool stop, const OdeSystem& system,
                     const std::string& option);
BranchRequest continue_request(const Arguments& args, const LoadedSystem& c);

// Writes `branch`'s JSON to `path` as continue --json does: the engine's branch JSON with the
// request's start and bounds, the case's path and parameter set, and the run time.
void write_branch_json(const std::string& path, const Branch& branch, const BranchRequest& request,
                       const LoadedSystem& c, double seconds);

// sympathy curve: the request (the branch, the event's name, the second parameter,
// the engine's CurveOptions, checked against the case `c`); the branch (computed as continue
// computes it, or read from --parent); and the event's curve (InputError naming --event for an
// event that has no curve).
struct CurveRequest {
  BranchRequest branch;  // its progress off
  EventName event;
  // --parent HOPF_CURVE.json --event GHn: the fold of cycles born there (no branch, no start).
  std::optional<GeneralizedHopfPoint> generalized_hopf;
  std::string second;
  int second_index = -1;
  CurveOptions options;
  std::string csv_path;   // "" for none: each point streamed here by follow_curve
  std::string json_path;  // "" for none: write_curve_json
};
CurveRequest curve_request(const Arguments& args, const LoadedSystem& c);
Branch curve_branch(const CurveRequest& r, const LoadedSystem& c, const BranchSource& source,
                    const std::atomic<bool>* stop);
// The curve, its points streamed to r.csv_path; with a describer each point and located event
// described (its maxima, minima, ...: one integration of its period each).
BifurcationCurve follow_curve(const CurveRequest& r, const OdeSystem& system, const Branch& parent,
                              const Bifurcation& event, const CurveCallbacks& callbacks,
                              const OrbitDescriber* describer = nullptr);
// The fold of cycles born at r.generalized_hopf (fold_of_cycles_from_generalized_hopf), streamed
// and described as follow_curve's; the Hopf point, family and fold it started from in `start`.
BifurcationCurve follow_generalized_hopf_fold(const CurveRequest& r, const OdeSystem& system,
                                              const CurveCallbacks& callbacks,
                                              const OrbitDescriber* describer,
                                              GeneralizedHopfFold& start);
// The curve's JSON to r.json_path, with the case's path and set, the start, the event's name and
// the run time.
// With the case's describer's groups for the points follow_curve described.
void write_curve_json(const CurveRequest& r, const BifurcationCurve& curve, const LoadedSystem& c,
                      double seconds);

// sympathy equilibria: the engine's problem and options read from them, checked
// against the case `c` (the problem's and the options' own checks, the range, the outputs).
struct EquilibriaRequest {
  std::string start;  // "" for an equation case file's [states]
  EquilibriumProblem problem;
  EquilibriumOptions options;
  std::string csv_path;   // "" for none: each point streamed here by run_equilibria
  std::string json_path;  // "" for none: write_equilibria_json
  // --switch-at BPn: the branch born at the parent's n-th branch point instead; the parent read
  // from --parent (its values the born branch's), or computed from the start over the window.
  int switch_at = 0;  // n; 0: no switch
  std::optional<EquilibriumBranch> parent;
  std::string parent_path;
  // ... or this one, already computed (a study's equilibria entry switched at another's BP).
  const EquilibriumBranch* parent_branch = nullptr;
};
EquilibriaRequest equilibria_request(const Arguments& args, const LoadedSystem& c);
// Where a branch of equilibria that is not switched starts, for `equilibria` and a study's
// [[equilibria]] entries: a saved point or event of an earlier run (`saved`, --parent F
// --from-point P: its state and every parameter value, AUTO's IRS with a label), or the case's
// start `start` ("" for an equation case file's [states]) with `initial` on top. `name` is what
// the reports and the JSON call it.
struct EquilibriaStart {
  Eigen::VectorXd state;
  ParameterValues values;
  std::string name;
};
EquilibriaStart equilibria_start(const LoadedSystem& c, const std::string& start,
                                 const std::vector<Assignment>& initial,
                                 const std::optional<SavedStart>& saved);
// The branch of equilibria (the engine's continue_equilibria, or with r.switch_at its
// continue_from_branch_point at the parent's BP), its points streamed to r.csv_path.
EquilibriumBranch run_equilibria(const EquilibriaRequest& r, const OdeSystem& system,
                                 const EquilibriumCallbacks& callbacks);
// The branch's JSON (the engine's equilibrium_branch_json) with the case's path and set, the
// start and the window: what `equilibria --json` writes and a study's JSON holds per entry.
nlohmann::json equilibria_json(const EquilibriaRequest& r, const EquilibriumBranch& branch,
                               const LoadedSystem& c);
// That JSON to r.json_path, with the run time.
void write_equilibria_json(const EquilibriaRequest& r, const EquilibriumBranch& branch,
                           const LoadedSystem& c, double seconds);

// sympathy simulate: the output times of --t-end and --dt (0, dt, 2 dt, ..., t_end;
// InputError unless 0 < dt <= t_end) and the integrator options on its defaults (BDF, rtol 1e-8,
// atol 1e-10).
std::vector<double> simulation_times(const Arguments& args);
FlowOptions simulation_flow_options(const Arguments& args);

}  // namespace sympathy::app
