// sympathy map: where each orbit of a map file is stable in two parameters. Per orbit: its branch
// in the first parameter at the case's values, the curve of every event located on it in both
// parameters (none twice), and its stability on a grid (the shading); one JSON for the figure
// (scripts/plot_map draws it) and a CSV per curve. The orbits run side by side.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>

#include "cases/app/branch_run.hpp"
#include "cases/app/map_file.hpp"
#include "cases/cli/case_arguments.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/progress.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/curve_output.hpp"
#include "sympathy/continuation/stability_map.hpp"

namespace sympathy::cli {

namespace {

struct OrbitMap {
  Branch branch;
  std::vector<BifurcationCurve> curves;
  StabilityGrid grid;
  std::string error;
  double seconds = 0.0;
};

int index_of(const OdeSystem& system, const std::string& name) {
  const auto names = system.parameter_names();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

}  // namespace

int run_map(const std::vector<std::string>& argv) {
  Arguments args("map", argv, map_options(), {"MAP"});
  Stopwatch clock;
  const MapStudy map = load_map(args.positional(0));
  const std::string out = args.text("--out", "out/figures");
  const int jobs = args.integer("--jobs", 2);
  if (jobs < 1) throw InputError("--jobs: expected a positive integer");
  const bool quiet = args.flag("--quiet");

  // The case (a metronome case file or an equation case file, compiled once), its parameters,
  // starts and marks checked before any work.
  const LoadedSystem c(map.case_path, map.params, {});
  c.require_autonomous("map (two-parameter curves)");
  for (const auto* axis : {&map.first, &map.second}) {
    const std::string which = axis == &map.first ? "first" : "second";
    c.require_parameter(map.path + ": " + which + ".parameter", axis->parameter);
    c.check_range(axis->parameter, {{map.path + ": " + which + ": from", axis->from},
                                    {map.path + ": " + which + ": to", axis->to}});
  }
  const double base_second = c.value_of(map.second.parameter);
  if (base_second < map.second.from || base_second > map.second.to)
    throw InputError(map.path + ": second: the window " + format_double(map.second.from) + " to " +
                     format_double(map.second.to) + " does not contain " + map.second.parameter +
                     " = " + format_double(base_second) + ", the value the branches start at");
  std::vector<BranchSource> sources;
  for (const auto& o : map.orbits) {
    if (o.start.empty() && !c.equations())
      throw InputError(map.path + ": orbit '" + o.name +
                       "': key 'start' is missing: expected one of the case's starts");
    sources.push_back(c.source(o.start, {}));  // throws naming the start if there is none
  }
  nlohmann::json marks = nlohmann::json::array();
  for (const auto& set : map.marks) {
    // In the map's plane only where every other parameter is the map's (Table III differs from
    // Table II in c as well as k: on the (k, M) map it is drawn hollow, off the plane).
    std::string off;
    double first = 0.0, second_value = 0.0;
    for (const auto& [name, value] : c.set_values(set)) {  // throws naming the set
      if (name == map.first.parameter)
        first = value;
      else if (name == map.second.parameter)
        second_value = value;
      else if (value != c.value_of(name))
        off += (off.empty() ? "" : ", ") + name + " = " + format_number(value);
    }
    marks.push_back({{"name", set},
                     {"first", first},
                     {"second", second_value},
                     {"in_plane", off.empty()},
                     {"off_plane", off}});
  }
  std::filesystem::create_directories(out);
  const std::string json_path = out + "/" + map.name + ".json";
  check_writable(json_path, map.path + ": the map's JSON");
  check_distinct_outputs({{"the map's JSON", json_path}}, with(c.inputs(), {"map file", map.path}));

  std::printf("sympathy map %s: %s\n  case %s  params %s  %s %g to %g, %s %g to %g\n",
              map.path.c_str(), map.title.c_str(), c.path().c_str(), c.params().c_str(),
              map.first.parameter.c_str(), map.first.from, map.first.to,
              map.second.parameter.c_str(), map.second.from, map.second.to);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const auto* stop = interrupt_flag();
  const OdeSystem& model = c.system();
  const int second = index_of(model, map.second.parameter);
  std::vector<OrbitMap> results(map.orbits.size());
  std::mutex print;
  ProgressLine progress(quiet);
  std::FILE* log = progress.log();
  progress.start_jobs("map", map.orbits.size(), "orbits");
  const auto say = [&](const char* format, auto... values) {
    if (quiet) return;
    std::lock_guard<std::mutex> lock(print);
    std::fprintf(log, format, values...);
  };
  std::size_t next = 0;
  auto worker = [&] {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> lock(print);
        if (next >= map.orbits.size()) return;
        i = next++;
      }
      const Stopwatch orbit_clock;
      OrbitMap& r = results[i];
      const MapOrbit& o = map.orbits[i];
      try {
        BranchRequest request;
        request.start = o.start;
        request.parameter = map.first.parameter;
        request.from = map.first.from;
        request.to = map.first.to;
        // The branch starts at the orbit's `at`, else at the case's own value where the window
        // holds it (the orbit the case's start reaches there, as the curves' seeds should be),
        // else at the window's `from`.
        const double own = c.value_of(map.first.parameter);
        request.at = o.at;
        if (!request.at && own > map.first.from && own < map.first.to) request.at = own;
        request.progress = nullptr;
        if (progress.enabled())
          request.on_point = [&, i](const ContinuationPoint& p) {
            progress.job(i, o.name + ": branch, " + map.first.parameter + " = " +
                                format_number(p.parameter));
          };
        apply_accuracy(args.has("--accuracy") ? accuracy(args) : map.accuracy,
                       request.continuation);
        r.branch = run_branch(sources[i], request, stop);
        say("  %s: branch of %zu points, %zu events in %.1f s\n", o.name.c_str(),
            r.branch.points.size(), r.branch.events.size(), r.branch.seconds);
        if (r.branch.started()) {
          CurveOptions co;
          co.first_lower = map.first.from;
          co.first_upper = map.first.to;
          co.second_lower = map.second.from;
          co.second_upper = map.second.to;
          co.orbit = request.continuation.orbit;
          CurveCallbacks cb;
          cb.stop_requested = [stop] { return stop->load(); };
          if (progress.enabled())
            cb.on_point = [&, i](const CurvePoint& p) {
              progress.job(i, o.name + ": curves, " + map.first.parameter + " = " +
                                  format_number(p.first) + ", " + map.second.parameter + " = " +
                                  format_number(p.second));
            };
          r.curves = event_curves(model, r.branch, second, co, cb);
          for (const auto& curve : r.curves)
            say("  %s: %s curve from %s, %zu points in %.1f s; %s\n", o.name.c_str(),
                to_string(curve.kind).c_str(), curve.origin.c_str(), curve.points.size(),
                curve.seconds, curve.stop_reason.c_str());
          if (map.first.points > 0 && !stop->load()) {
            progress.job(i, o.name + ": the stability grid");
            r.grid =
                stability_grid(model, r.branch, second, map.first.from, map.first.to,
                               map.second.from, map.second.to, map.first.points, map.second.points,
                               request.continuation.orbit, [stop] { return stop->load(); });
            say("  %s: stability on a %d x %d grid in %.1f s (%d points without an orbit)\n",
                o.name.c_str(), map.first.points, map.second.points, r.grid.seconds,
                r.grid.failures);
          }
        }
      } catch (const std::exception& e) {
        r.error = e.what();
      }
      r.seconds = orbit_clock.seconds();
      progress.finish(i);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::min<int>(jobs, static_cast<int>(map.orbits.size())); ++t)
    threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  progress.clear();

  nlohmann::json j;
  j["map"] = map.name;
  j["title"] = map.title;
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["first"] = {{"parameter", map.first.parameter}, {"from", map.first.from}, {"to", map.first.to}};
  j["second"] = {
      {"parameter", map.second.parameter}, {"from", map.second.from}, {"to", map.second.to}};
  j["marks"] = marks;
  j["orbits"] = nlohmann::json::array();
  bool ok = true;
  int files = 0;
  for (std::size_t i = 0; i < map.orbits.size(); ++i) {
    const OrbitMap& r = results[i];
    nlohmann::json o;
    o["name"] = map.orbits[i].name;
    o["start"] = map.orbits[i].start;
    o["seconds"] = r.seconds;
    if (!r.error.empty()) o["error"] = r.error;
    o["branch"] = branch_json(r.branch);
    o["curves"] = nlohmann::json::array();
    int number = 0;
    for (const auto& curve : r.curves) {
      nlohmann::json cj = curve_json(curve);
      const std::string csv = map.name + "-" + map.orbits[i].name + "-" + to_string(curve.kind) +
                              std::to_string(++number) + ".csv";
      CurveCsvWriter writer(out + "/" + csv, model, map.first.parameter, map.second.parameter);
      for (const auto& p : curve.points) writer.write(p);
      writer.close();
      ++files;
      cj["csv"] = csv;
      o["curves"].push_back(cj);
    }
    if (!r.grid.first.empty())
      o["grid"] = {{"first", r.grid.first},
                   {"second", r.grid.second},
                   {"unstable_count", r.grid.unstable_count},
                   {"seconds", r.grid.seconds}};
    j["orbits"].push_back(o);
    ok = ok && r.error.empty() && r.branch.started();
    std::printf("%s: %s\n", map.orbits[i].name.c_str(),
                !r.error.empty() ? r.error.c_str() : r.branch.stop_reason.c_str());
    // The stop column as wide as its longest entry ("minimum step / parameter bound": 32).
    const auto stops_of = [](const BifurcationCurve& curve) {
      return (curve.backward_stop ? to_string(*curve.backward_stop) + " / " : std::string()) +
             to_string(curve.stop);
    };
    int width = 4;
    for (const auto& curve : r.curves)
      width = std::max(width, static_cast<int>(stops_of(curve).size()));
    std::printf("  curve     from                         points  %-*s run time  codim-2 points\n",
                width, "stop");
    for (const auto& curve : r.curves) {
      std::string codim2;
      for (const auto& e : curve.events)
        if (e.type.rfind("turn", 0) != 0)
          codim2 += (codim2.empty() ? "" : ", ") + e.type + " at " + format_number(e.first) + ", " +
                    format_number(e.second);
      std::printf("  %-9s %-28s %6zu  %-*s %6.1f s  %s\n", to_string(curve.kind).c_str(),
                  curve.origin.c_str(), curve.points.size(), width, stops_of(curve).c_str(),
                  curve.seconds, codim2.empty() ? "none" : codim2.c_str());
    }
  }
  j["seconds"] = clock.seconds();
  write_json(json_path, j);
  std::printf("  wrote %s and %d CSV files of curves; run time %.1f s\n", json_path.c_str(), files,
              clock.seconds());
  // A branch or curve stopped short of its window for a numerical reason: exit code 7 (a curve
  // that could not start from its event is reported in its row, as the map's own finding).
  int code = ok ? kDone : kNumericalFailure;
  for (const OrbitMap& r : results) {
    if (r.branch.started()) code = worse(code, exit_code_of(r.branch));
    for (const auto& curve : r.curves)
      if (exit_code_of(curve) == kStoppedShort) code = worse(code, kStoppedShort);
  }
  return stop->load() ? kInterrupted : code;
}

}  // namespace sympathy::cli
