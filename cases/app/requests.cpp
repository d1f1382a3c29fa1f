#include "cases/app/requests.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "cases/app/event_name.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/start_data.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/equilibrium_output.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/option_check.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

OrbitOptions orbit_request(const Arguments& args, bool forced) {
  OrbitOptions o;
  o.shooting.segments = args.integer("--segments", 1);
  o.shooting.threads = segment_threads(args);
  // A forced system's orbit: Newton from the start at once unless a transient is asked for (its
  // period is known; a transient would leave an unstable response for whatever attracts).
  o.transient = args.number("--transient", forced ? 0.0 : o.transient);
  o.max_period = args.number("--max-period", o.max_period);
  apply_accuracy(accuracy(args), o);
  shooting_flow_options(args, o);
  o.use_symmetry = !args.flag("--whole-state");
  check_options(o.validate(), "");
  return o;
}

ContinuationOptions branch_continuation(const Arguments& args, const OdeSystem& system) {
  ContinuationOptions o;
  // A forced system's start: Newton at once unless a transient is asked for (its period is the
  // forcing's; a transient would leave an unstable response for whatever attracts).
  o.orbit.transient = args.number("--transient", system.autonomous() ? o.orbit.transient : 0.0);
  o.orbit.max_period = args.number("--max-period", o.orbit.max_period);
  o.orbit.shooting.segments = args.integer("--segments", 1);
  o.initial_step = args.number("--step", o.initial_step);
  o.max_step = args.number("--max-step", o.max_step);
  o.max_points = args.integer("--max-points", o.max_points);
  apply_accuracy(accuracy(args), o);
  shooting_flow_options(args, o.orbit);
  return o;
}

UserValue user_value(const Assignment& a, bool stop, const OdeSystem& system,
                     const std::string& option) {
  UserValue v;
  v.value = a.value;
  v.stop = stop;
  v.name = a.key;
  const auto names = system.state_names();
  const auto state = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
  };
  if (a.key == "period") {
    if (!system.autonomous())
      throw InputError(option + " period=" + format_number(a.value) +
                       ": a forced system's period is the forcing's; expected max_NAME, "
                       "min_NAME or NAME");
    if (!(a.value > 0.0))
      throw InputError(option + " period=" + format_number(a.value) +
                       ": expected a positive period");
    v.quantity = UserValue::Quantity::Period;
    return v;
  }
  if (state(a.key) >= 0) {  // a state's value at the orbit's section point
    v.quantity = UserValue::Quantity::AtSection;
    v.state = state(a.key);
    return v;
  }
  for (const auto& [prefix, quantity] :
       {std::pair{std::string("max_"), UserValue::Quantity::Maximum},
        std::pair{std::string("min_"), UserValue::Quantity::Minimum}})
    if (a.key.rfind(prefix, 0) == 0 && state(a.key.substr(prefix.size())) >= 0) {
      v.quantity = quantity;
      v.state = state(a.key.substr(prefix.size()));
      return v;
    }
  std::vector<std::string> expected{"period"};
  for (const auto& n : names) expected.push_back("max_" + n);
  for (const auto& n : names) expected.push_back("min_" + n);
  for (const auto& n : names) expected.push_back(n);
  throw InputError(option + " " + a.key + "=" + format_number(a.value) +
                   ": not a quantity of the orbits; expected one of: " + join(expected));
}

BranchRequest continue_request(const Arguments& args, const LoadedSystem& c) {
  const ParameterWindow window = parameter_window(args, c);
  BranchRequest request;
  request.start_data = c.start_data();
  c.require_orbits();
  const auto saved = saved_start(args);
  if (saved && !c.saved_orbit()) {
    // A point of a saved Hopf curve of equilibria: the family of orbits born there.
    if (args.command() != "continue")
      throw InputError("--parent " + saved->path +
                       ": a Hopf curve of equilibria; its points start families of orbits "
                       "(continue --parent FILE --from-point N), not one orbit");
    request.hopf_point =
        read_hopf_curve_point(*saved, c.system(), c.system().parameter_index(window.parameter));
    request.hopf_point_name = "point " + saved->what + " of the Hopf curve " + saved->path;
  }
  if (!c.equations() && !args.has("--start") && !request.start_data && !c.saved_orbit() &&
      !request.hopf_point)
    throw InputError(
        "--start is required (or --start-data FILE.csv, or --parent FILE --from-point POINT)");
  request.start = args.text("--start", "");
  // A Hopf curve's family needs no start; a metronome case's source still names one (unused).
  if (request.hopf_point && request.start.empty() && !c.equations() && !c.start_names().empty())
    request.start = c.start_names().front();
  request.parameter = window.parameter;
  request.from = window.from;
  request.to = window.to;
  request.at = window.at;
  request.initial = args.assignments("--initial");
  request.period_guess = period_guess(args);
  request.csv_path = args.text("--csv", "");
  request.switch_at = args.text("--switch-at", "");
  if (!request.switch_at.empty() && !parse_hopf_name(request.switch_at, "--switch-at"))
    parse_event_name(request.switch_at, "--switch-at",
                     {BifurcationType::BranchPoint, BifurcationType::PeriodDoubling},
                     "a branch point or period doubling of the branch, or a Hopf point of the "
                     "equilibria (BP, PD or HB followed by its number, e.g. BP1 or HB1): only "
                     "there is a branch born");
  if (!request.switch_at.empty()) c.require_autonomous("--switch-at (branch switching)");
  if (args.has("--hopf-amplitude")) {
    if (request.switch_at.empty() || !parse_hopf_name(request.switch_at, "--switch-at"))
      throw InputError(
          "--hopf-amplitude: only with --switch-at HBn (the family born at a Hopf point); "
          "expected --switch-at HB1, HB2, ... or no --hopf-amplitude");
    request.hopf_start.amplitude = args.number("--hopf-amplitude", 0.0);
    if (!(request.hopf_start.amplitude > 0.0))
      throw InputError("--hopf-amplitude " + format_number(request.hopf_start.amplitude) +
                       ": expected a positive amplitude (state units)");
  }
  request.parent_path = args.text("--parent", "");
  // The start's file (a saved orbit's, a Hopf curve's), not a parent to switch in.
  if (c.saved_orbit() || request.hopf_point) request.parent_path.clear();
  if (!request.parent_path.empty() && request.switch_at.empty())
    throw InputError("--parent " + request.parent_path +
                     ": expected --switch-at EVENT (the event of the parent to switch at) or "
                     "--from-point POINT (the saved orbit to start from) too");

  if (args.flag("--quiet")) request.progress = nullptr;
  request.verbose = args.flag("--verbose");
  auto& o = request.continuation;
  o = branch_continuation(args, c.system());
  if (c.saved_orbit() && !args.has("--segments"))
    o.orbit.shooting.segments = c.saved_orbit()->segments;  // what it was resolved on
  o.orbit.shooting.threads = segment_threads(args);
  o.user_points = args.numbers("--user-points");
  for (double v : o.user_points)
    if (v < std::min(request.from, request.to) || v > std::max(request.from, request.to))
      throw InputError("--user-points " + format_number(v) + ": outside --from " +
                       format_number(request.from) + " .. --to " + format_number(request.to) +
                       "; expected values the branch can reach");
  for (const bool stop : {false, true})
    for (const Assignment& a : args.assignments(stop ? "--stop-at" : "--user-value"))
      o.user_values.push_back(user_value(a, stop, c.system(), stop ? "--stop-at" : "--user-value"));
  o.orbit.use_symmetry = !args.flag("--whole-state");
  check_options(o.validate(), "");
  c.check_range(request.parameter, window.ends());
  // The start (fails early with the list of starts).
  c.source(request.start, request.initial, request.start_data);
  const auto json_path = args.value("--json");
  if (json_path) check_writable(*json_path, "--json");
  request.events_path = args.text("--events", "");
  if (!request.csv_path.empty()) check_writable(request.csv_path, "--csv");
  if (!request.events_path.empty()) check_writable(request.events_path, "--events");
  auto inputs = c.inputs();
  inputs.emplace_back("--parent", request.parent_path);
  inputs.emplace_back("--start-data", args.text("--start-data", ""));
  check_distinct_outputs({{"--csv", request.csv_path},
                          {"--events", request.events_path},
                          {"--json", json_path.value_or("")}},
                         inputs);

  return request;
}

EquilibriaRequest equilibria_request(const Arguments& args, const LoadedSystem& c) {
  c.require_autonomous("equilibria");
  EquilibriaRequest r;
  const OdeSystem& system = c.system();
  const ParameterWindow window = parameter_window(args, c);
  if (!c.equations() && !args.has("--start")) throw InputError("--start is required");
  r.start = args.text("--start", "");
  const std::string& parameter = window.parameter;

  EquilibriumProblem& problem = r.problem;
  problem.parameter = system.parameter_index(parameter);
  problem.from = window.from;
  problem.to = window.to;
  problem.at = window.at;
  c.check_range(parameter, window.ends());
  const auto saved = saved_start(args);  // refuses --from-point beside --switch-at
  if (args.has("--switch-at")) {
    const EventName name = parse_event_name(
        args.text("--switch-at", ""), "--switch-at", {BifurcationType::BranchPoint},
        "a branch point of the equilibria, BP followed by its number along them (e.g. BP1): only "
        "there is a branch of equilibria born (the orbits born at a Hopf point: continue "
        "--switch-at HB1)");
    r.switch_at = name.ordinal;
    if (problem.at)
      throw InputError("--at: not with --switch-at " + name.text +
                       " (the born branch runs both ways from its branch point)");
  }
  r.parent_path = args.text("--parent", "");
  if (!r.parent_path.empty() && !r.switch_at && !args.has("--from-point"))
    throw InputError("--parent " + r.parent_path +
                     ": expected --switch-at BPn (the branch point to switch at) or --from-point "
                     "POINT (the saved equilibrium to start from) too");
  if (r.switch_at && !r.parent_path.empty()) {
    // The parent's branch points and every parameter value, read and checked before any work.
    EquilibriumBranch parent = read_equilibria_json(r.parent_path, system);
    if (parent.parameter_name != parameter)
      throw InputError("--parent " + r.parent_path + ": equilibria in " + parent.parameter_name +
                       "; expected them in --param " + parameter +
                       " (a branch point is one in "
                       "the parameter its branch was continued in)");
    int bps = 0;
    for (const auto& e : parent.events) bps += e.type == EquilibriumEventType::BranchPoint;
    if (bps < r.switch_at)
      throw InputError("--switch-at BP" + std::to_string(r.switch_at) + ": --parent " +
                       r.parent_path + " has " + std::to_string(bps) +
                       " branch point(s); expected BP1 .. BP" + std::to_string(bps));
    problem.start_state = Eigen::VectorXd::Zero(system.dimension());  // the BP's, when run
    problem.values = parent.start_values;
    r.start = "the branch point BP" + std::to_string(r.switch_at) + " of " + r.parent_path;
    r.parent = std::move(parent);
  } else {
    EquilibriaStart start = equilibria_start(c, r.start, args.assignments("--initial"), saved);
    problem.start_state = std::move(start.state);
    problem.values = std::move(start.values);
    r.start = start.name;
  }
  if (const std::string wrong = problem.problem_with(system); !wrong.empty())
    throw InputError("--" + wrong);
  EquilibriumOptions& o = r.options;
  o.initial_step = args.number("--step", o.initial_step);
  o.max_step = args.number("--max-step", o.max_step);
  o.max_points = args.integer("--max-points", o.max_points);
  o.lower = std::min(problem.from, problem.to);
  o.upper = std::max(problem.from, problem.to);
  o.user_points = args.numbers("--user-points");
  for (double v : o.user_points)
    if (v < o.lower || v > o.upper)
      throw InputError("--user-points " + format_number(v) + ": outside --from " +
                       format_number(problem.from) + " .. --to " + format_number(problem.to) +
                       "; expected values the branch can reach");
  check_options(o.validate(), "");
  r.csv_path = args.text("--csv", "");
  const std::string& csv_path = r.csv_path;
  r.json_path = args.text("--json", "");
  if (!csv_path.empty()) check_writable(csv_path, "--csv");
  if (!r.json_path.empty()) check_writable(r.json_path, "--json");
  check_distinct_outputs({{"--csv", csv_path}, {"--json", r.json_path}}, c.inputs());

  return r;
}

EquilibriaStart equilibria_start(const LoadedSystem& c, const std::string& start,
                                 const std::vector<Assignment>& initial,
                                 const std::optional<SavedStart>& saved) {
  if (saved) {
    // In the same parameter or another.
    SavedEquilibrium e = read_saved_equilibrium(*saved, c.system());
    return {std::move(e.state), std::move(e.values), "saved " + e.description};
  }
  BranchSource source = c.source(start, initial);  // throws naming the start if there is none
  return {std::move(source.start_state), std::move(source.values), start};
}

std::vector<double> simulation_times(const Arguments& args) {
  const double t_end = args.number("--t-end", 60.0);
  const double dt = args.number("--dt", 0.01);
  if (!(t_end > 0.0)) throw InputError("--t-end: expected a positive number of seconds");
  if (!(dt > 0.0 && dt <= t_end)) throw InputError("--dt: expected a positive interval <= --t-end");
  if (t_end / dt > kMaxSamples)
    throw InputError("--dt " + args.text("--dt", "") + ": " + format_double(t_end / dt) +
                     " samples over --t-end " + format_double(t_end) +
                     "; expected at most 1e7 samples (a larger --dt or a shorter --t-end)");
  return sample_times(t_end, dt);
}

FlowOptions simulation_flow_options(const Arguments& args) {
  FlowOptions defaults;
  defaults.rtol = 1e-8;
  defaults.atol = 1e-10;
  return flow_options(args, defaults);
}

void write_branch_json(const std::string& path, const Branch& branch, const BranchRequest& request,
                       const LoadedSystem& c, double seconds) {
  nlohmann::json j = branch_json(branch, request, c.describer());
  if (c.saved_orbit()) j["start"] = "saved " + c.saved_orbit()->description;
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["seconds"] = seconds;
  write_json(path, j);
}

namespace {

// The branch born at the parent's r.switch_at-th branch point: the parent read (r.parent) or
// computed over the window (its progress not streamed: the born branch's is); a parent without
// that many BPs ends the run as a failed start, saying how many it has.
EquilibriumBranch switch_at_branch_point(const EquilibriaRequest& r, const OdeSystem& system,
                                         const EquilibriumCallbacks& callbacks) {
  EquilibriumBranch computed;
  if (!r.parent && !r.parent_branch) {
    EquilibriumCallbacks quiet;
    quiet.stop_requested = callbacks.stop_requested;
    computed = continue_equilibria(system, r.problem, r.options, quiet);
  }
  const EquilibriumBranch& parent = r.parent_branch ? *r.parent_branch
                                    : r.parent      ? *r.parent
                                                    : computed;
  EquilibriumBranch failed;
  failed.parameter = r.problem.parameter;
  failed.parameter_name = system.parameter_names()[r.problem.parameter];
  failed.state_names = system.state_names();
  failed.stop = StopReason::StartFailed;
  if (!parent.started()) {
    failed.stop_reason = "no equilibria to switch at: " + parent.stop_reason;
    return failed;
  }
  const EquilibriumEvent* bp = nullptr;
  int seen = 0;
  for (const auto& e : parent.events)
    if (e.type == EquilibriumEventType::BranchPoint && ++seen == r.switch_at) bp = &e;
  if (!bp) {
    failed.stop_reason = "the equilibria through the start have " + std::to_string(seen) +
                         " branch point(s) in the window; no BP" + std::to_string(r.switch_at);
    return failed;
  }
  EquilibriumProblem problem = r.problem;
  problem.values = parent.start_values;
  return continue_from_branch_point(system, problem, *bp, r.options, callbacks);
}

}  // namespace

EquilibriumBranch run_equilibria(const EquilibriaRequest& r, const OdeSystem& system,
                                 const EquilibriumCallbacks& callbacks) {
  // Each point streamed to the CSV as it is found, before the caller's hook sees it.
  std::unique_ptr<EquilibriumCsvWriter> csv;
  if (!r.csv_path.empty())
    csv = std::make_unique<EquilibriumCsvWriter>(r.csv_path, system,
                                                 system.parameter_names()[r.problem.parameter]);
  EquilibriumCallbacks streamed = callbacks;
  streamed.on_point = [&](const EquilibriumPoint& p) {
    if (csv) csv->write(p);
    if (callbacks.on_point) callbacks.on_point(p);
  };
  EquilibriumBranch branch = r.switch_at
                                 ? switch_at_branch_point(r, system, streamed)
                                 : continue_equilibria(system, r.problem, r.options, streamed);
  if (csv) csv->close();
  return branch;
}

nlohmann::json equilibria_json(const EquilibriaRequest& r, const EquilibriumBranch& branch,
                               const LoadedSystem& c) {
  nlohmann::json j = equilibrium_branch_json(branch);
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["start"] = r.start;
  j["from"] = r.problem.from;
  j["to"] = r.problem.to;
  return j;
}

void write_equilibria_json(const EquilibriaRequest& r, const EquilibriumBranch& branch,
                           const LoadedSystem& c, double seconds) {
  nlohmann::json j = equilibria_json(r, branch, c);
  j["seconds"] = seconds;
  write_json(r.json_path, j);
}

}  // namespace sympathy::app
