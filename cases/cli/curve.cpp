// sympathy curve: the two-parameter curve of a bifurcation located on a branch (LP, BP, PD, NS),
// followed in a second parameter; the branch computed as `continue` computes it, or read from
// its JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/progress.hpp"
#include "cases/cli/requests.hpp"
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/curve_output.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

namespace {

void print_curve_events(std::FILE* out, const BifurcationCurve& curve) {
  if (curve.events.empty()) {
    std::fprintf(out, "  none\n");
    return;
  }
  std::fprintf(out, "  %-10s %-20s %-20s %-11s %s\n", "type", curve.first_name.c_str(),
               curve.second_name.c_str(), "uncertainty", "note");
  for (const auto& e : curve.events)
    std::fprintf(out, "  %-10s %-20.12g %-20.12g %-11.1e %s%s%s\n", e.type.c_str(), e.first,
                 e.second, e.uncertainty, e.description.c_str(), e.note.empty() ? "" : "; ",
                 e.note.c_str());
}

}  // namespace

CurveRequest curve_request(const Arguments& args, const LoadedSystem& c) {
  c.require_autonomous("curve (two-parameter curves)");
  const ParameterWindow window = parameter_window(args, c);
  CurveRequest r;
  BranchRequest& request = r.branch;
  request.start_data = c.start_data();
  if (!c.equations() && !args.has("--start") && !request.start_data)
    throw InputError("--start is required (or --start-data FILE.csv)");
  request.start = args.text("--start", "");
  request.parameter = window.parameter;
  c.require_parameter("--second", *args.value("--second"));
  r.second = *args.value("--second");
  const std::string& second = r.second;
  if (second == request.parameter)
    throw InputError("--second " + second + ": expected a parameter other than --param");
  r.event = parse_event_name(
      *args.value("--event"), "--event",
      {BifurcationType::Fold, BifurcationType::BranchPoint, BifurcationType::PeriodDoubling,
       BifurcationType::NeimarkSacker},
      "a located bifurcation, LP, BP, PD or NS followed by its number along the branch (e.g. "
      "BP1)");
  request.from = window.from;
  request.to = window.to;
  request.initial = args.assignments("--initial");
  request.progress = nullptr;
  request.parent_path = args.text("--parent", "");
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
  co.orbit = o.orbit;
  check_options(co.validate(), "");  // names initial_step --step, ...
  c.check_range(request.parameter, {{"--from", request.from}, {"--to", request.to}});
  c.check_range(second, {{"--second-from", co.second_lower}, {"--second-to", co.second_upper}});
  c.source(request.start, request.initial, request.start_data);  // fails early: the starts
  // The curve starts at the branch's value of the second parameter: the window must hold it.
  const double base_second = c.value_of(second);
  if (base_second < co.second_lower || base_second > co.second_upper)
    throw InputError("--second-from, --second-to: the window " + format_double(co.second_lower) +
                     " to " + format_double(co.second_upper) + " does not contain the event (" +
                     second + " = " + format_double(base_second) + " on the branch)");
  const auto names = c.system().parameter_names();
  r.second_index = static_cast<int>(std::find(names.begin(), names.end(), second) - names.begin());
  r.csv_path = args.text("--csv", "");
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

BifurcationCurve follow_curve(const CurveRequest& r, const OdeSystem& system, const Branch& parent,
                              const Bifurcation& event, const CurveCallbacks& callbacks) {
  try {
    return continue_curve(system, parent, event, r.second_index, r.options, callbacks);
  } catch (const std::invalid_argument& e) {
    throw InputError("--event " + r.event.text + ": " + e.what());
  }
}

int run_curve(const std::vector<std::string>& argv) {
  Arguments args("curve", argv, curve_options(), {"CASE"});
  Stopwatch clock;
  const LoadedSystem c = load_system(args);
  const CurveRequest r = curve_request(args, c);
  const BranchRequest& request = r.branch;
  const EventName& name = r.event;
  const std::string& second = r.second;
  const CurveOptions& curve_options = r.options;
  const BranchSource source = c.source(request.start, request.initial, request.start_data);
  const auto json_path = args.value("--json");
  const std::string csv_path = args.text("--csv", "");
  if (json_path) check_writable(*json_path, "--json");
  if (!csv_path.empty()) check_writable(csv_path, "--csv");
  check_distinct_outputs({{"--csv", csv_path}, {"--json", json_path.value_or("")}},
                         with(c.inputs(), {"--parent", request.parent_path}));

  std::printf(
      "sympathy curve %s  params %s  start %s  %s of the %s-branch (%g to %g) in %s "
      "(%g to %g)\n",
      c.path().c_str(), c.params().empty() ? "(none)" : c.params().c_str(),
      request.start_data      ? describe_start_data(*request.start_data).c_str()
      : request.start.empty() ? "(the file's [states])"
                              : request.start.c_str(),
      name.text.c_str(), request.parameter.c_str(), request.from, request.to, second.c_str(),
      curve_options.second_lower, curve_options.second_upper);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const OdeSystem& model = c.system();
  const Branch parent = curve_branch(r, c, source, interrupt_flag());
  if (!parent.started()) {
    std::printf("  the branch: %s\n  run time %.3f s\n", parent.stop_reason.c_str(),
                clock.seconds());
    return kNumericalFailure;
  }
  if (interrupt_flag()->load()) return kInterrupted;
  const Bifurcation& event = find_event(parent, name, "--event");
  std::printf("  the branch: %zu points %s; %s at %s = %.10g\n", parent.points.size(),
              request.parent_path.empty()
                  ? ("in " + format_number(std::round(parent.seconds * 100) / 100) + " s").c_str()
                  : ("from " + request.parent_path).c_str(),
              name.text.c_str(), request.parameter.c_str(), event.parameter);
  std::fflush(stdout);

  std::unique_ptr<CurveCsvWriter> csv;
  if (!csv_path.empty())
    csv = std::make_unique<CurveCsvWriter>(csv_path, model, request.parameter, second);
  const bool quiet = args.flag("--quiet");
  ProgressLine progress(quiet);
  std::FILE* log = progress.log();
  int points = 0;
  CurveCallbacks callbacks;
  callbacks.on_point = [&](const CurvePoint& p) {
    if (csv) csv->write(p);
    if (!quiet) {
      std::fprintf(log, "  [%4d] %s = %-14.9g %s = %-14.9g T = %.9f s  critical %.6f%+.6fi",
                   p.index, request.parameter.c_str(), p.first, second.c_str(), p.second, p.period,
                   p.critical.empty() ? NAN : p.critical[0].real(),
                   p.critical.empty() ? NAN : p.critical[0].imag());
      if (std::isfinite(p.rotation)) std::fprintf(log, "  rotation %.6f", p.rotation);
      std::fprintf(log, "  (%d it)\n", p.iterations);
    }
    progress.show("curve " + name.text + ": " + request.parameter + " = " + format_number(p.first) +
                  ", " + second + " = " + format_number(p.second) + ", " +
                  std::to_string(++points) + " points, " + duration_text(clock.seconds()));
  };
  callbacks.on_event = [&](const CurveEvent& e) {
    if (!quiet)
      std::fprintf(log, "  >> %s at %s = %.10g, %s = %.10g\n", e.type.c_str(),
                   request.parameter.c_str(), e.first, second.c_str(), e.second);
  };
  callbacks.stop_requested = [] { return interrupt_flag()->load(); };
  const BifurcationCurve curve = follow_curve(r, model, parent, event, callbacks);
  progress.clear();
  if (csv) csv->close();
  std::printf("  %zu points; stopped: %s\n", curve.points.size(), curve.stop_reason.c_str());
  std::printf("codimension-two points and turns:\n");
  print_curve_events(stdout, curve);
  std::printf("  run time %.3f s (the curve %.3f s: %d monodromies, %ld steps; noise %.1e)\n",
              clock.seconds(), curve.seconds, curve.evaluations, curve.flow.steps, curve.noise);
  if (json_path) {
    nlohmann::json j = curve_json(curve);
    j["case"] = c.path();
    j["params_set"] = c.params();
    j["start"] = request.start;
    j["event"] = name.text;
    j["seconds"] = clock.seconds();
    write_json(*json_path, j);
  }
  return exit_code_of(curve);
}

}  // namespace sympathy::cli
