#include "cases/app/map_run.hpp"

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <thread>

#include "cases/app/requests.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/curve_output.hpp"
#include "sympathy/continuation/equilibrium_output.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/output_file.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

namespace {

int index_of(const OdeSystem& system, const std::string& name) {
  const auto names = system.parameter_names();
  return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
}

// A curve's window: the map's (the cycles' CurveOptions, the equilibria's).
template <class Options>
void set_window(Options& o, const MapStudy& map) {
  o.first_lower = map.first.from;
  o.first_upper = map.first.to;
  o.second_lower = map.second.from;
  o.second_upper = map.second.to;
}

}  // namespace

MapRun prepare_map(const MapRequest& request) {
  if (request.jobs < 1) throw InputError("--jobs: expected a positive integer");
  MapRun run;
  run.request = request;
  run.map = load_map(request.path);
  const MapStudy& map = run.map;
  // The case (a metronome case file or an equation case file, compiled once), its parameters,
  // starts and marks checked before any work.
  // A piecewise-smooth model's orbits are mapped; its equilibria lie on its surfaces.
  run.system = std::make_unique<LoadedSystem>(
      map.case_path, map.params, std::vector<Assignment>{}, std::nullopt,
      map.equilibria.empty() ? "a map" : "a map's [[equilibria]]", std::nullopt, map.escapement);
  const LoadedSystem& c = *run.system;
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
  for (const auto& o : map.orbits) {
    if (o.saved) {
      // A saved orbit: its own parameter values, its second one inside the window.
      const SavedOrbit saved = read_saved_orbit(*o.saved, c.system());
      const double second =
          c.system().parameter(saved.values, index_of(c.system(), map.second.parameter));
      if (second < map.second.from || second > map.second.to)
        throw InputError(map.path + ": orbit '" + o.name + "': its saved orbit has " +
                         map.second.parameter + " = " + format_double(second) +
                         ", outside the second window");
      run.sources.push_back({c.system(), c.describer(), saved.values, saved.state0,
                             InvariantSubspace(), "saved " + saved.description, saved.period});
      run.saved_segments.push_back(saved.segments);
      continue;
    }
    if (o.start.empty() && !c.equations())
      throw InputError(map.path + ": orbit '" + o.name +
                       "': key 'start' is missing: expected one of the case's starts");
    run.sources.push_back(c.source(o.start, {}));  // throws naming the start if there is none
    run.saved_segments.push_back(0);
  }
  const int first = index_of(c.system(), map.first.parameter);
  for (const auto& e : map.equilibria) {
    EquilibriumProblem problem;
    problem.parameter = first;
    problem.from = map.first.from;
    problem.to = map.first.to;
    if (e.start.empty() && !e.saved && !c.equations())
      throw InputError(map.path + ": equilibria '" + e.name +
                       "': key 'start' is missing: expected one of the case's starts");
    EquilibriaStart start = equilibria_start(c, e.start, {}, e.saved);  // throws naming it
    problem.start_state = std::move(start.state);
    problem.values = std::move(start.values);
    run.equilibria_starts.push_back(start.name.empty() ? "the case's states" : start.name);
    // A saved equilibrium has its own parameter values: its second one inside the window.
    const double second =
        c.system().parameter(problem.values, index_of(c.system(), map.second.parameter));
    if (e.saved && (second < map.second.from || second > map.second.to))
      throw InputError(map.path + ": equilibria '" + e.name + "': its saved equilibrium has " +
                       map.second.parameter + " = " + format_double(second) +
                       ", outside the second window");
    // Found at the entry's `at`, else at its own value where the window holds it (as the
    // orbits' branches), and followed both ways.
    const double own = c.system().parameter(problem.values, first);
    problem.at = e.at;
    if (!problem.at && own > map.first.from && own < map.first.to) problem.at = own;
    if (const std::string wrong = problem.problem_with(c.system()); !wrong.empty())
      throw InputError(map.path + ": equilibria '" + e.name + "': " + wrong);
    run.equilibria.push_back(std::move(problem));
  }
  run.marks = nlohmann::json::array();
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
    run.marks.push_back({{"name", set},
                         {"first", first},
                         {"second", second_value},
                         {"in_plane", off.empty()},
                         {"off_plane", off}});
  }
  std::filesystem::create_directories(request.out);
  run.json_path = request.out + "/" + map.name + ".json";
  check_writable(run.json_path, map.path + ": the map's JSON");
  check_distinct_outputs({{"the map's JSON", run.json_path}},
                         with(c.inputs(), {"map file", map.path}));
  return run;
}

void run_map(MapRun& run, const std::atomic<bool>* stop, const JobCallbacks& callbacks) {
  const MapStudy& map = run.map;
  const LoadedSystem& c = *run.system;
  const OdeSystem& model = c.system();
  const int second = index_of(model, map.second.parameter);
  const auto stopped = [stop] { return stop && stop->load(); };
  run.results.assign(map.orbits.size(), MapOrbitResult{});
  run.equilibria_results.assign(map.equilibria.size(), MapEquilibriaResult{});
  std::mutex lock;
  const auto job = [&](std::size_t i, const std::string& what) {
    if (callbacks.job) callbacks.job(i, what);
  };
  const auto log = [&](const std::string& line) {
    if (!callbacks.log) return;
    std::lock_guard<std::mutex> guard(lock);
    callbacks.log(line);
  };
  // One [[equilibria]] entry: its branch in the first parameter, then the curves of its events.
  const auto equilibria = [&](std::size_t i) {
    const std::size_t k = i - map.orbits.size();
    MapEquilibriaResult& r = run.equilibria_results[k];
    const MapEquilibria& e = map.equilibria[k];
    EquilibriumOptions options;
    options.lower = map.first.from;
    options.upper = map.first.to;
    EquilibriumCallbacks branch_callbacks;
    branch_callbacks.stop_requested = stopped;
    if (callbacks.job)
      branch_callbacks.on_point = [&, i](const EquilibriumPoint& p) {
        job(i,
            e.name + ": equilibria, " + map.first.parameter + " = " + format_number(p.parameter));
      };
    r.branch = continue_equilibria(model, run.equilibria[k], options, branch_callbacks);
    char line[256];
    std::snprintf(line, sizeof line, "  %s: equilibria, %zu points, %zu events in %.1f s\n",
                  e.name.c_str(), r.branch.points.size(), r.branch.events.size(), r.branch.seconds);
    log(line);
    if (!r.branch.started()) return;
    EquilibriumCurveOptions co;
    set_window(co, map);
    EquilibriumCurveCallbacks cb;
    cb.stop_requested = stopped;
    if (callbacks.job)
      cb.on_point = [&, i](const EquilibriumCurvePoint& p) {
        job(i, e.name + ": curves, " + map.first.parameter + " = " + format_number(p.first) + ", " +
                   map.second.parameter + " = " + format_number(p.second));
      };
    r.curves = equilibrium_event_curves(model, r.branch, second, co, cb);
    for (const auto& curve : r.curves) {
      std::snprintf(line, sizeof line, "  %s: %s curve from %s, %zu points in %.1f s; %s\n",
                    e.name.c_str(), to_string(curve.kind).c_str(), curve.origin.c_str(),
                    curve.points.size(), curve.seconds, curve.stop_reason.c_str());
      log(line);
    }
  };
  // One orbit: its branch, the curves of its events, its stability grid.
  const auto orbit = [&](std::size_t i) {
    MapOrbitResult& r = run.results[i];
    const MapOrbit& o = map.orbits[i];
    BranchRequest request;
    request.start = o.start;
    request.parameter = map.first.parameter;
    request.from = map.first.from;
    request.to = map.first.to;
    // The branch starts at the orbit's `at`, else at the case's own value where the window
    // holds it (the orbit the case's start reaches there, as the curves' seeds should be),
    // else at the window's `from`.
    const double own = o.saved ? c.system().parameter(run.sources[i].values,
                                                      index_of(c.system(), map.first.parameter))
                               : c.value_of(map.first.parameter);
    request.at = o.at;
    if (!request.at && own > map.first.from && own < map.first.to) request.at = own;
    request.progress = nullptr;
    if (callbacks.job)
      request.on_point = [&, i](const ContinuationPoint& p) {
        job(i, o.name + ": branch, " + map.first.parameter + " = " + format_number(p.parameter));
      };
    apply_accuracy(run.request.accuracy.value_or(map.accuracy), request.continuation);
    if (run.saved_segments[i] > 0)  // on the segments it was resolved on
      request.continuation.orbit.shooting.segments = run.saved_segments[i];
    r.branch = run_branch(run.sources[i], request, stop);
    char line[256];
    std::snprintf(line, sizeof line, "  %s: branch of %zu points, %zu events in %.1f s\n",
                  o.name.c_str(), r.branch.points.size(), r.branch.events.size(), r.branch.seconds);
    log(line);
    if (r.branch.started()) {
      CurveOptions co;
      set_window(co, map);
      co.orbit = request.continuation.orbit;
      CurveCallbacks cb;
      cb.stop_requested = stopped;
      if (callbacks.job)
        cb.on_point = [&, i](const CurvePoint& p) {
          job(i, o.name + ": curves, " + map.first.parameter + " = " + format_number(p.first) +
                     ", " + map.second.parameter + " = " + format_number(p.second));
        };
      r.curves = event_curves(model, r.branch, second, co, cb);
      for (const auto& curve : r.curves) {
        std::snprintf(line, sizeof line, "  %s: %s curve from %s, %zu points in %.1f s; %s\n",
                      o.name.c_str(), to_string(curve.kind).c_str(), curve.origin.c_str(),
                      curve.points.size(), curve.seconds, curve.stop_reason.c_str());
        log(line);
      }
      if (map.first.points > 0 && !stopped()) {
        job(i, o.name + ": the stability grid");
        r.grid = stability_grid(model, r.branch, second, map.first.from, map.first.to,
                                map.second.from, map.second.to, map.first.points, map.second.points,
                                request.continuation.orbit, stopped);
        std::snprintf(line, sizeof line,
                      "  %s: stability on a %d x %d grid in %.1f s (%d points without an "
                      "orbit)\n",
                      o.name.c_str(), map.first.points, map.second.points, r.grid.seconds,
                      r.grid.failures);
        log(line);
      }
    }
  };
  std::size_t next = 0;
  auto worker = [&] {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> guard(lock);
        if (next >= run.jobs()) return;
        i = next++;
      }
      const Stopwatch clock;
      const bool is_orbit = i < map.orbits.size();
      std::string& error =
          is_orbit ? run.results[i].error : run.equilibria_results[i - map.orbits.size()].error;
      try {
        if (is_orbit)
          orbit(i);
        else
          equilibria(i);
      } catch (const std::exception& e) {
        error = e.what();
      }
      (is_orbit ? run.results[i].seconds : run.equilibria_results[i - map.orbits.size()].seconds) =
          clock.seconds();
      if (callbacks.finished) callbacks.finished(i);
    }
  };
  std::vector<std::thread> threads;
  const int jobs = std::min<int>(run.request.jobs, static_cast<int>(run.jobs()));
  for (int t = 0; t < jobs; ++t) threads.emplace_back(worker);
  for (auto& t : threads) t.join();
}

int write_map(const MapRun& run, double seconds) {
  const MapStudy& map = run.map;
  const LoadedSystem& c = *run.system;
  nlohmann::json j;
  j["map"] = map.name;
  j["title"] = map.title;
  j["case"] = c.path();
  j["params_set"] = c.params();
  j["first"] = {{"parameter", map.first.parameter}, {"from", map.first.from}, {"to", map.first.to}};
  j["second"] = {
      {"parameter", map.second.parameter}, {"from", map.second.from}, {"to", map.second.to}};
  j["marks"] = run.marks;
  j["orbits"] = nlohmann::json::array();
  int files = 0;
  for (std::size_t i = 0; i < map.orbits.size(); ++i) {
    const MapOrbitResult& r = run.results[i];
    nlohmann::json o;
    o["name"] = map.orbits[i].name;
    o["start"] = map.orbits[i].saved ? run.sources[i].start_name : map.orbits[i].start;
    o["seconds"] = r.seconds;
    if (!r.error.empty()) o["error"] = r.error;
    o["branch"] = branch_json(r.branch);
    o["curves"] = nlohmann::json::array();
    int number = 0;
    for (const auto& curve : r.curves) {
      nlohmann::json cj = curve_json(curve);
      const std::string csv = map.name + "-" + map.orbits[i].name + "-" + to_string(curve.kind) +
                              std::to_string(++number) + ".csv";
      CurveCsvWriter writer(run.request.out + "/" + csv, c.system(), map.first.parameter,
                            map.second.parameter);
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
  }
  j["equilibria"] = nlohmann::json::array();
  for (std::size_t k = 0; k < map.equilibria.size(); ++k) {
    const MapEquilibriaResult& r = run.equilibria_results[k];
    nlohmann::json e;
    e["name"] = map.equilibria[k].name;
    e["start"] = run.equilibria_starts[k];
    e["seconds"] = r.seconds;
    if (!r.error.empty()) e["error"] = r.error;
    e["branch"] = equilibrium_branch_json(r.branch);
    e["curves"] = nlohmann::json::array();
    int number = 0;
    for (const auto& curve : r.curves) {
      nlohmann::json cj = equilibrium_curve_json(curve);
      const std::string csv = map.name + "-" + map.equilibria[k].name + "-" +
                              to_string(curve.kind) + std::to_string(++number) + ".csv";
      EquilibriumCurveCsvWriter writer(run.request.out + "/" + csv, c.system(), map.first.parameter,
                                       map.second.parameter);
      for (const auto& p : curve.points) writer.write(p);
      writer.close();
      ++files;
      cj["csv"] = csv;
      e["curves"].push_back(cj);
    }
    j["equilibria"].push_back(e);
  }
  j["seconds"] = seconds;
  write_json(run.json_path, j);
  return files;
}

}  // namespace sympathy::app
