// sympathy map: the map file's request read from the command line (cases/app/map_run.hpp computes
// it), progress on a terminal, the table of each orbit's curves printed, the exit code.
#include <algorithm>
#include <cstdio>

#include "cases/app/map_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"

namespace sympathy::cli {

namespace {

// A job's curves, a row each: kind, origin, points, how each half stopped, run time, and the
// codimension-two points `shown` keeps (not the cycles' turns, not user values).
template <class Curve, class Shown>
void print_curves(const std::vector<Curve>& curves, const Shown& shown) {
  // The stop column as wide as its longest entry ("minimum step / parameter bound": 32).
  const auto stops_of = [](const Curve& curve) {
    return (curve.backward_stop ? to_string(*curve.backward_stop) + " / " : std::string()) +
           to_string(curve.stop);
  };
  int width = 4;
  for (const auto& curve : curves)
    width = std::max(width, static_cast<int>(stops_of(curve).size()));
  std::printf("  curve     from                         points  %-*s run time  codim-2 points\n",
              width, "stop");
  for (const auto& curve : curves) {
    std::string codim2;
    for (const auto& e : curve.events)
      if (shown(e))
        codim2 += (codim2.empty() ? "" : ", ") + e.type + " at " + format_number(e.first) + ", " +
                  format_number(e.second);
    std::printf("  %-9s %-28s %6zu  %-*s %6.1f s  %s\n", to_string(curve.kind).c_str(),
                curve.origin.c_str(), curve.points.size(), width, stops_of(curve).c_str(),
                curve.seconds, codim2.empty() ? "none" : codim2.c_str());
  }
}

}  // namespace

int run_map(const std::vector<std::string>& argv) {
  Arguments args("map", argv, map_options(), {"MAP"});
  Stopwatch clock;
  MapRequest request;
  request.path = args.positional(0);
  request.out = args.text("--out", request.out);
  request.jobs = args.integer("--jobs", request.jobs);
  if (args.has("--accuracy")) request.accuracy = accuracy(args);
  const bool quiet = args.flag("--quiet");
  MapRun run = prepare_map(request);  // every check before any work
  const MapStudy& map = run.map;
  const LoadedSystem& c = *run.system;

  std::printf("sympathy map %s: %s\n  case %s  params %s  %s %g to %g, %s %g to %g\n",
              map.path.c_str(), map.title.c_str(), c.path().c_str(), c.params().c_str(),
              map.first.parameter.c_str(), map.first.from, map.first.to,
              map.second.parameter.c_str(), map.second.from, map.second.to);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const auto* stop = interrupt_flag();
  ProgressLine progress(quiet);
  std::FILE* log = progress.log();
  progress.start_jobs("map", run.jobs(), "jobs");
  JobCallbacks callbacks;
  if (progress.enabled())
    callbacks.job = [&](std::size_t i, const std::string& what) { progress.job(i, what); };
  if (!quiet) callbacks.log = [&](const std::string& line) { std::fputs(line.c_str(), log); };
  callbacks.finished = [&](std::size_t i) { progress.finish(i); };
  run_map(run, stop, callbacks);
  progress.clear();

  bool ok = true;
  for (std::size_t i = 0; i < map.orbits.size(); ++i) {
    const MapOrbitResult& r = run.results[i];
    ok = ok && r.error.empty() && r.branch.started();
    std::printf("%s: %s\n", map.orbits[i].name.c_str(),
                !r.error.empty() ? r.error.c_str() : r.branch.stop_reason.c_str());
    print_curves(r.curves, [](const CurveEvent& e) { return e.type.rfind("turn", 0) != 0; });
  }
  for (std::size_t k = 0; k < map.equilibria.size(); ++k) {
    const MapEquilibriaResult& r = run.equilibria_results[k];
    ok = ok && r.error.empty() && r.branch.started();
    std::printf("%s (equilibria): %s\n", map.equilibria[k].name.c_str(),
                !r.error.empty() ? r.error.c_str() : r.branch.stop_reason.c_str());
    print_curves(r.curves, [](const EquilibriumCurveEvent& e) { return e.type != "UZ"; });
  }
  const int files = write_map(run, clock.seconds());
  std::printf("  wrote %s and %d CSV files of curves; run time %.1f s\n", run.json_path.c_str(),
              files, clock.seconds());
  // A branch or curve stopped short of its window for a numerical reason: exit code 7 (a curve
  // that could not start from its event is reported in its row, as the map's own finding).
  int code = ok ? kDone : kNumericalFailure;
  const auto add = [&code](const auto& results) {
    for (const auto& r : results) {
      if (r.branch.started()) code = worse(code, exit_code_of(r.branch));
      for (const auto& curve : r.curves)
        if (exit_code_of(curve) == kStoppedShort) code = worse(code, kStoppedShort);
    }
  };
  add(run.results);
  add(run.equilibria_results);
  return stop->load() ? kInterrupted : code;
}

}  // namespace sympathy::cli
