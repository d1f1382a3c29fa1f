#include "cases/app/requests.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

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
  if (!c.equations() && !args.has("--start") && !request.start_data && !c.saved_orbit())
    throw InputError(
        "--start is required (or --start-data FILE.csv, or --parent FILE --from-point POINT)");
  request.start = args.text("--start", "");
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
  if (c.saved_orbit()) request.parent_path.clear();  // the start's file, not a parent to switch in
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
  if (const auto saved = saved_start(args)) {
    // A point or event of an earlier equilibria run (AUTO's IRS with a label): its state and
    // every parameter value, in the same parameter or another.
    const SavedEquilibrium e = read_saved_equilibrium(*saved, system);
    problem.start_state = e.state;
    problem.values = e.values;
    r.start = "saved " + e.description;
  } else {
    const BranchSource source = c.source(r.start, args.assignments("--initial"));
    problem.start_state = source.start_state;
    problem.values = source.values;
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
  EquilibriumBranch branch = continue_equilibria(system, r.problem, r.options, streamed);
  if (csv) csv->close();
  return branch;
}

void write_equilibria_json(const EquilibriaRequest& r, const EquilibriumBranch& branch,
                           const LoadedSystem& c, double seconds) {
  nlohmann::json j = equilibrium_branch_json(branch);
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["start"] = r.start;
  j["from"] = r.problem.from;
  j["to"] = r.problem.to;
  j["seconds"] = seconds;
  write_json(r.json_path, j);
}

}  // namespace sympathy::app
