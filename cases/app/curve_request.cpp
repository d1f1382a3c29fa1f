#include "cases/app/requests.hpp"

#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/curve_output.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <memory>
#include <optional>

#include "cases/app/hopf_switch.hpp"
#include "cases/app/start_data.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/option_check.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

CurveRequest curve_request(const Arguments& args, const LoadedSystem& c) {
  c.require_autonomous("curve (two-parameter curves)");
  const ParameterWindow window = parameter_window(args, c);
  CurveRequest r;
  BranchRequest& request = r.branch;
  request.parent_path = args.text("--parent", "");
  // From a generalized Hopf point of a Hopf curve of equilibria: no branch, no start.
  if (!request.parent_path.empty() && holds_hopf_curve(request.parent_path)) {
    r.event.text = *args.value("--event");
    r.event.type = BifurcationType::Fold;
    r.generalized_hopf =
        read_generalized_hopf(request.parent_path, r.event.text, "--event", c.system());
  }
  request.start_data = c.start_data();
  if (!r.generalized_hopf && !c.equations() && !args.has("--start") && !request.start_data)
    throw InputError("--start is required (or --start-data FILE.csv)");
  request.start = args.text("--start", "");
  request.parameter = window.parameter;
  c.require_parameter("--second", *args.value("--second"));
  r.second = *args.value("--second");
  const std::string& second = r.second;
  if (second == request.parameter)
    throw InputError("--second " + second + ": expected a parameter other than --param");
  if (!r.generalized_hopf)
    r.event = parse_event_name(
        *args.value("--event"), "--event",
        {BifurcationType::Fold, BifurcationType::BranchPoint, BifurcationType::PeriodDoubling,
         BifurcationType::NeimarkSacker},
        "a located bifurcation, LP, BP, PD or NS followed by its number along the branch (e.g. "
        "BP1)");
  const auto names = c.system().parameter_names();
  if (r.generalized_hopf) {
    const std::string& first_name = names[r.generalized_hopf->at.first];
    const std::string& second_name = names[r.generalized_hopf->at.second];
    if (request.parameter != first_name || second != second_name)
      throw InputError("--param " + request.parameter + ", --second " + second + ": " +
                       request.parent_path + " is a Hopf curve in " + first_name + " and " +
                       second_name + "; expected --param " + first_name + " --second " +
                       second_name);
  }
  request.from = window.from;
  request.to = window.to;
  request.initial = args.assignments("--initial");
  request.progress = nullptr;
  auto& o = request.continuation;
  o.orbit.transient = args.number("--transient", o.orbit.transient);
  apply_accuracy(accuracy(args), o);
  shooting_flow_options(args, o.orbit);
  check_options(o.validate(), "");

  CurveOptions& co = r.options;
  co.first_lower = std::min(request.from, request.to);
  co.first_upper = std::max(request.from, request.to);
  co.second_lower = args.number("--second-from", 0.0);
  co.second_upper = args.number("--second-to", 0.0);
  if (co.second_lower > co.second_upper) std::swap(co.second_lower, co.second_upper);
  if (co.second_lower == co.second_upper)
    throw InputError("--second-from and --second-to: expected different values");
  co.initial_step = args.number("--step", co.initial_step);
  co.max_step = args.number("--max-step", co.max_step);
  co.max_points = args.integer("--max-points", co.max_points);
  // The period, or either parameter's value: UZ there (and the curve's end with --stop-at).
  for (const bool stop : {false, true}) {
    const std::string option = stop ? "--stop-at" : "--user-value";
    for (const Assignment& a : args.assignments(option)) {
      if (a.key == request.parameter || a.key == second) {
        UserValue v;
        v.quantity = UserValue::Quantity::Parameter;
        v.parameter = c.system().parameter_index(a.key);
        v.value = a.value;
        v.stop = stop;
        v.name = a.key;
        co.user_values.push_back(v);
        continue;
      }
      if (a.key != "period")
        throw InputError(option + " " + a.key + "=" + format_number(a.value) +
                         ": a curve's points carry their period and parameters only; expected "
                         "period=VALUE, " +
                         request.parameter + "=VALUE or " + second + "=VALUE");
      co.user_values.push_back(user_value(a, stop, c.system(), option));
    }
  }
  co.orbit = o.orbit;
  check_options(co.validate(), "");  // names initial_step --step, ...
  c.check_range(request.parameter, {{"--from", request.from}, {"--to", request.to}});
  c.check_range(second, {{"--second-from", co.second_lower}, {"--second-to", co.second_upper}});
  if (!r.generalized_hopf)
    c.source(request.start, request.initial, request.start_data);  // fails early: the starts
  // The curve starts at the branch's value of the second parameter (at the GH's, near it): the
  // window must hold it.
  const double base_second =
      r.generalized_hopf
          ? c.system().parameter(r.generalized_hopf->at.values, r.generalized_hopf->at.second)
          : c.value_of(second);
  if (base_second < co.second_lower || base_second > co.second_upper)
    throw InputError("--second-from, --second-to: the window " + format_double(co.second_lower) +
                     " to " + format_double(co.second_upper) + " does not contain the event (" +
                     second + " = " + format_double(base_second) +
                     (r.generalized_hopf ? " at " + r.event.text + ")" : " on the branch)"));
  if (r.generalized_hopf) {
    const double at =
        c.system().parameter(r.generalized_hopf->at.values, r.generalized_hopf->at.first);
    if (at < co.first_lower || at > co.first_upper)
      throw InputError("--from, --to: the window " + format_double(co.first_lower) + " to " +
                       format_double(co.first_upper) + " does not contain " + r.event.text + " (" +
                       request.parameter + " = " + format_double(at) + ")");
  }
  r.second_index = static_cast<int>(std::find(names.begin(), names.end(), second) - names.begin());
  r.csv_path = args.text("--csv", "");
  // Every output checked before any work: writable, and none replacing an input or another.
  r.json_path = args.text("--json", "");
  if (!r.json_path.empty()) check_writable(r.json_path, "--json");
  if (!r.csv_path.empty()) check_writable(r.csv_path, "--csv");
  check_distinct_outputs({{"--csv", r.csv_path}, {"--json", r.json_path}},
                         with(c.inputs(), {"--parent", request.parent_path}));
  return r;
}

Branch curve_branch(const CurveRequest& r, const LoadedSystem& c, const BranchSource& source,
                    const std::atomic<bool>* stop) {
  if (r.branch.parent_path.empty()) return run_branch(source, r.branch, stop);
  Branch parent = read_branch_json(r.branch.parent_path, c.system(), c.subspace(r.branch.start));
  if (parent.parameter_name != r.branch.parameter)
    throw InputError("--parent " + r.branch.parent_path + ": a branch in " + parent.parameter_name +
                     "; expected one in --param " + r.branch.parameter);
  return parent;
}

namespace {

// `run`'s curve (in the parameters first and r.second_index, the others at `base`), each point
// described and streamed to the CSV as it is found, before the caller's hook sees it; its
// description kept by its index for the curve's points.
BifurcationCurve streamed_curve(const CurveRequest& r, const OdeSystem& system,
                                const ParameterValues& base, int first,
                                const std::function<BifurcationCurve(const CurveCallbacks&)>& run,
                                const CurveCallbacks& callbacks, const OrbitDescriber* describer) {
  std::unique_ptr<CurveCsvWriter> csv;
  if (!r.csv_path.empty())
    csv = std::make_unique<CurveCsvWriter>(r.csv_path, system, r.branch.parameter, r.second,
                                           describer);
  const auto describe = [&](const CurvePoint& p) {
    return describer->describe(curve_point_orbit(system, base, first, r.second_index, p));
  };
  std::map<int, std::vector<double>> descriptions;
  CurveCallbacks streamed = callbacks;
  streamed.on_point = [&](const CurvePoint& p) {
    CurvePoint q = p;
    if (describer) q.description = describe(q);
    if (csv) csv->write(q);
    if (callbacks.on_point) callbacks.on_point(q);
    descriptions[q.index] = std::move(q.description);
  };
  try {
    BifurcationCurve curve = run(streamed);
    if (csv) csv->close();
    if (describer) {
      for (auto& p : curve.points)
        if (auto it = descriptions.find(p.index); it != descriptions.end())
          p.description = std::move(it->second);
      for (auto& e : curve.events) e.at.description = describe(e.at);
    }
    return curve;
  } catch (const std::invalid_argument& e) {
    throw InputError("--event " + r.event.text + ": " + e.what());
  }
}

}  // namespace

BifurcationCurve follow_curve(const CurveRequest& r, const OdeSystem& system, const Branch& parent,
                              const Bifurcation& event, const CurveCallbacks& callbacks,
                              const OrbitDescriber* describer) {
  const ParameterValues base =
      system.with_parameter(parent.start_values, parent.parameter, event.parameter);
  return streamed_curve(
      r, system, base, parent.parameter,
      [&](const CurveCallbacks& streamed) {
        return continue_curve(system, parent, event, r.second_index, r.options, streamed);
      },
      callbacks, describer);
}

BifurcationCurve follow_generalized_hopf_fold(const CurveRequest& r, const OdeSystem& system,
                                              const CurveCallbacks& callbacks,
                                              const OrbitDescriber* describer,
                                              GeneralizedHopfFold& start) {
  const GeneralizedHopfPoint& gh = *r.generalized_hopf;
  GeneralizedHopfOptions options;
  options.curve = r.options;
  options.family = r.branch.continuation;
  ContinuationCallbacks family;
  family.stop_requested = callbacks.stop_requested;
  return streamed_curve(
      r, system, gh.at.values, gh.at.first,
      [&](const CurveCallbacks& streamed) {
        start = fold_of_cycles_from_generalized_hopf(system, gh, options, family, streamed);
        return start.curve;
      },
      callbacks, describer);
}

void write_curve_json(const CurveRequest& r, const BifurcationCurve& curve, const LoadedSystem& c,
                      double seconds) {
  nlohmann::json j = curve_json(curve, &c.describer());
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["start"] = r.branch.start;
  j["event"] = r.event.text;
  j["seconds"] = seconds;
  write_json(r.json_path, j);
}

}  // namespace sympathy::app
