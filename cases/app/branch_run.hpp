// A branch of a case, as `continue` and `study` ask for it: the case's named start and parameter
// turned into the engine's BranchProblem, progress lines and the streamed CSV hooked to the
// engine's callbacks, and the events table. The work is the engine's (continue_branch).
#pragma once

#include <atomic>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/app/case_loading.hpp"
#include "cases/app/event_name.hpp"
#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/hopf.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/continuation/recorded_period.hpp"

namespace sympathy::app {

struct BranchRequest {
  std::string start;
  std::string parameter;
  double from = 0.0, to = 0.0;
  std::optional<double> at;         // start here and go both ways
  std::vector<Assignment> initial;  // state values on top of the start
  // Instead of the start: one recorded period (--start-data), Newton from it in the whole state.
  std::optional<RecordedPeriod> start_data;
  std::string csv_path;              // "" for none
  std::string events_path;           // located events streamed here ("" for none)
  ContinuationOptions continuation;  // bounds are set from from/to
  std::FILE* progress = stderr;      // nullptr: quiet
  bool verbose = false;              // multipliers on each progress line
  // "BP1", "PD2": continue the branch born at that event of the branch asked for instead (its
  // points and events are what the CSV, the events file and the result hold).
  std::string switch_at;
  // --period-guess: Newton at once from the start state with this period (no transient).
  std::optional<double> period_guess;
  // With switch_at a Hopf point (HBn): how the family's first orbit is found there.
  HopfStartOptions hopf_start;
  // The family born at this Hopf point instead (a point of a saved Hopf curve of equilibria,
  // --parent HOPF.json --from-point N), named `hopf_point_name`.
  std::optional<HopfPoint> hopf_point;
  std::string hopf_point_name;
  // With switch_at: the parent branch read from this JSON (written by continue --json) instead
  // of computed ...
  std::string parent_path;
  // ... or this one, already computed (a study branch that switches at an event of another).
  const Branch* parent_branch = nullptr;
  // With switch_at HBn: these equilibria, already computed (a study branch that switches at a
  // Hopf point of the study's [[equilibria]] entry), instead of parent_path's or the start's.
  const EquilibriumBranch* parent_equilibria = nullptr;
  // A caller's own hooks (the Python module's progress callback and signal check): each point of
  // the branch returned, as it is found (after the CSV row), and a stop check asked beside
  // run_branch's flag.
  std::function<void(const ContinuationPoint&)> on_point;
  std::function<bool()> stop_requested;
};

// What a branch needs from a case of either kind (a metronome case file, an equation case
// file): the system, the parameter values the run starts from, the start's state, name and
// invariant subspace, and the describer of its orbits.
struct BranchSource {
  const OdeSystem& system;
  const OrbitDescriber& describer;
  ParameterValues values;
  Eigen::VectorXd start_state;
  InvariantSubspace subspace;
  std::string start_name;
  std::optional<double> start_period;  // a recorded period's guess: Newton at once (BranchProblem)
};

// A branch read back from the JSON `continue --json` wrote, with what switching at its events
// needs: the parameter, every parameter value, and per event its located orbit, unknowns and
// tangent; its points carry `subspace` (the start's). InputError naming the file and the key for
// anything missing or of the wrong size for `model`.
Branch read_branch_json(const std::string& path, const OdeSystem& model,
                        const InvariantSubspace& subspace);

// The event of `branch` so named; InputError listing the branch's events if there is none.
const Bifurcation& find_event(const Branch& branch, const EventName& name,
                              const std::string& option);

// Runs the branch. Throws InputError for a request that does not fit the case, OutputError when
// the CSV cannot be written.
Branch run_branch(const BranchSource& source, const BranchRequest& request,
                  const std::atomic<bool>* stop);
// The same for a metronome case: the model must be built from `c.spec`; the start is the case's
// named start request.start, with request.initial on top.
Branch run_branch(const LoadedCase& c, const MetronomeModel& model, const BranchRequest& request,
                  const std::atomic<bool>* stop);

// The engine's branch JSON with the request's start and bounds.
nlohmann::json branch_json(const Branch& branch, const BranchRequest& request,
                           const OrbitDescriber& describer);

}  // namespace sympathy::app
