#include "cases/app/equilibrium_curve_run.hpp"

#include <algorithm>
#include <memory>
#include <regex>

#include "cases/app/case_arguments.hpp"
#include "cases/app/case_loading.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/json_reader.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/equilibrium_output.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

bool wants_equilibrium_curve(const Arguments& args) {
  const std::string path = args.text("--parent", "");
  if (path.empty()) return false;
  const JsonReader file(path, "a branch JSON (continue --json) or equilibria (equilibria --json)");
  const nlohmann::json& j = file.root();
  if (!j.is_object()) return false;
  if (j.contains("kind") && j["kind"] == "equilibria") return true;
  // A curve of equilibria: the curve through one of its codimension-two points; but from a GH of
  // a Hopf curve the fold of cycles born there, a curve of cycles.
  const bool generalized_hopf =
      args.text("--event", "").rfind("GH", 0) == 0 && j.contains("kind") && j["kind"] == "HB";
  return j.contains("of") && j["of"] == "equilibria" && !generalized_hopf;
}

namespace {
EquilibriumCurveRequest finish_request(const Arguments& args, const LoadedSystem& c,
                                       const ParameterWindow& window, EquilibriumCurveRequest& r);
}  // namespace

EquilibriumCurveRequest equilibrium_curve_request(const Arguments& args, const LoadedSystem& c) {
  c.require_autonomous("curve (two-parameter curves)");
  const OdeSystem& system = c.system();
  EquilibriumCurveRequest r;
  r.parent_path = args.text("--parent", "");
  for (const char* own :
       {"--start", "--initial", "--start-data", "--transient", "--set", "--params"})
    if (args.has(own))
      throw InputError(std::string(own) + ": not with --parent " + r.parent_path +
                       " (equilibria: the curve starts at their event, at their parameter "
                       "values)");
  const ParameterWindow window = parameter_window(args, c);
  r.event_name = *args.value("--event");
  if (holds_curve_of_equilibria(r.parent_path)) {
    // The other curve through a codimension-two point of a curve of equilibria: the point's
    // parameters are the curve's.
    r.codimension_two =
        read_curve_of_equilibria_event(r.parent_path, r.event_name, "--event", system).point;
    const auto names = system.parameter_names();
    const std::string& first = names[r.codimension_two->first];
    const std::string& second = names[r.codimension_two->second];
    if (window.parameter != first || *args.value("--second") != second)
      throw InputError("--param " + window.parameter + ", --second " + *args.value("--second") +
                       ": " + r.parent_path + " is a curve in " + first + " and " + second +
                       "; expected --param " + first + " --second " + second);
    r.second = r.codimension_two->second;
    r.parent.parameter = r.codimension_two->first;
    r.parent.parameter_name = first;
    r.parent.start_values = r.codimension_two->values;
    r.event.parameter = system.parameter(r.codimension_two->values, r.codimension_two->first);
    r.event.state = r.codimension_two->state;
    return finish_request(args, c, window, r);
  }
  r.parent = read_equilibria_json(r.parent_path, system);
  if (r.parent.parameter_name != window.parameter)
    throw InputError("--parent " + r.parent_path + ": equilibria in " + r.parent.parameter_name +
                     "; expected them in --param " + window.parameter);
  // LPn or HBn: the n-th of that type along the parent.
  std::smatch m;
  if (!std::regex_match(r.event_name, m, std::regex("(LP|HB)([1-9][0-9]{0,5})")))
    throw InputError("--event " + r.event_name +
                     ": expected a fold or Hopf point of the equilibria, LP or HB followed by its "
                     "number along them (e.g. HB1): only their curves continue in two parameters");
  const EquilibriumEventType type =
      m[1] == "LP" ? EquilibriumEventType::Fold : EquilibriumEventType::Hopf;
  const int ordinal = std::stoi(m[2]);
  int seen = 0;
  bool found = false;
  for (const auto& e : r.parent.events)
    if (e.type == type && ++seen == ordinal) {
      r.event = e;
      found = true;
      break;
    }
  if (!found)
    throw InputError("--event " + r.event_name + ": --parent " + r.parent_path + " has " +
                     std::to_string(seen) + " " + to_string(type) + " point(s)");
  const std::string second = *args.value("--second");
  c.require_parameter("--second", second);
  if (second == window.parameter)
    throw InputError("--second " + second + ": expected a parameter other than --param");
  r.second = system.parameter_index(second);
  return finish_request(args, c, window, r);
}

namespace {

// The options, windows and outputs of either start (an event of equilibria, a codimension-two
// point of a curve of them), checked.
EquilibriumCurveRequest finish_request(const Arguments& args, const LoadedSystem& c,
                                       const ParameterWindow& window, EquilibriumCurveRequest& r) {
  const OdeSystem& system = c.system();
  const std::string second = system.parameter_names()[r.second];
  EquilibriumCurveOptions& o = r.options;
  o.first_lower = std::min(window.from, window.to);
  o.first_upper = std::max(window.from, window.to);
  o.second_lower = args.number("--second-from", 0.0);
  o.second_upper = args.number("--second-to", 0.0);
  if (o.second_lower > o.second_upper) std::swap(o.second_lower, o.second_upper);
  if (o.second_lower == o.second_upper)
    throw InputError("--second-from and --second-to: expected different values");
  o.initial_step = args.number("--step", o.initial_step);
  o.max_step = args.number("--max-step", o.max_step);
  o.max_points = args.integer("--max-points", o.max_points);
  // Values of either parameter: UZ there (and the curve's end with --stop-at).
  for (const bool stop : {false, true}) {
    const std::string option = stop ? "--stop-at" : "--user-value";
    for (const Assignment& a : args.assignments(option)) {
      if (a.key != window.parameter && a.key != second)
        throw InputError(option + " " + a.key + "=" + format_number(a.value) +
                         ": a curve of equilibria reports values of its parameters; expected " +
                         window.parameter + "=VALUE or " + second + "=VALUE");
      o.user_values.push_back({a.key == second, a.value, stop});
    }
  }
  check_options(o.validate(), "");
  if (r.event.parameter < o.first_lower || r.event.parameter > o.first_upper)
    throw InputError("--from, --to: the window does not hold " + r.event_name + " at " +
                     window.parameter + " = " + format_double(r.event.parameter));
  const double at = system.parameter(r.parent.start_values, r.second);
  if (at < o.second_lower || at > o.second_upper)
    throw InputError("--second-from, --second-to: the window does not hold the " +
                     std::string(r.codimension_two ? r.event_name + "'s " : "equilibria's ") +
                     second + " = " + format_double(at));
  r.csv_path = args.text("--csv", "");
  r.json_path = args.text("--json", "");
  if (!r.csv_path.empty()) check_writable(r.csv_path, "--csv");
  if (!r.json_path.empty()) check_writable(r.json_path, "--json");
  auto inputs = c.inputs();
  inputs.emplace_back("--parent", r.parent_path);
  check_distinct_outputs({{"--csv", r.csv_path}, {"--json", r.json_path}}, inputs);
  return r;
}

}  // namespace

EquilibriumCurve run_equilibrium_curve(const EquilibriumCurveRequest& r, const OdeSystem& system,
                                       const EquilibriumCurveCallbacks& callbacks) {
  std::unique_ptr<EquilibriumCurveCsvWriter> csv;
  if (!r.csv_path.empty())
    csv = std::make_unique<EquilibriumCurveCsvWriter>(r.csv_path, system, r.parent.parameter_name,
                                                      system.parameter_names()[r.second]);
  EquilibriumCurveCallbacks streamed = callbacks;
  streamed.on_point = [&](const EquilibriumCurvePoint& p) {
    if (csv) csv->write(p);
    if (callbacks.on_point) callbacks.on_point(p);
  };
  try {
    EquilibriumCurve curve =
        r.codimension_two
            ? continue_from_codimension_two(system, *r.codimension_two, r.options, streamed)
            : continue_equilibrium_curve(system, r.parent, r.event, r.second, r.options, streamed);
    if (csv) csv->close();
    return curve;
  } catch (const std::invalid_argument& e) {
    throw InputError("--event " + r.event_name + ": " + e.what());
  }
}

void write_equilibrium_curve_json(const EquilibriumCurveRequest& r, const EquilibriumCurve& curve,
                                  const LoadedSystem& c, double seconds) {
  nlohmann::json j = equilibrium_curve_json(curve);
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["parent"] = r.parent_path;
  j["event"] = r.event_name;
  j["seconds"] = seconds;
  write_json(r.json_path, j);
}

}  // namespace sympathy::app
