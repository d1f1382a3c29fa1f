// sympathy map as a request, below the command line and Python: where each orbit of a map file is
// stable in two parameters. Per orbit: its branch in the first parameter at the case's values,
// the curve of every event located on it in both parameters (none twice), and its stability on a
// grid; the orbits side by side on `jobs` threads; one JSON for the figure (scripts/plot_map draws
// it) and a CSV per curve.
#pragma once

#include <atomic>
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/app/branch_run.hpp"
#include "cases/app/job_callbacks.hpp"
#include "cases/app/loaded_system.hpp"
#include "cases/app/map_file.hpp"
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/equilibrium_map.hpp"
#include "sympathy/continuation/stability_map.hpp"

namespace sympathy::app {

struct MapRequest {
  std::string path;                  // the map file
  std::string out = "out/figures";   // where the JSON and CSV files go
  int jobs = 2;                      // orbits computed side by side
  std::optional<Accuracy> accuracy;  // else the map file's
};

struct MapOrbitResult {
  Branch branch;
  std::vector<BifurcationCurve> curves;
  StabilityGrid grid;
  std::string error;  // why the orbit has no result ("" where it has)
  double seconds = 0.0;
};

struct MapEquilibriaResult {
  EquilibriumBranch branch;
  std::vector<EquilibriumCurve> curves;  // of its LP and HB points, and from their BT, ZH, HH
  std::string error;                     // why the entry has no result ("" where it has)
  double seconds = 0.0;
};

// A map run: the map file read and every check made before any work (the case, its parameters
// and window, the orbits' starts, the marks' parameter sets, the outputs), then its results.
struct MapRun {
  MapRequest request;
  MapStudy map;
  std::unique_ptr<LoadedSystem> system;
  std::vector<BranchSource> sources;  // per orbit
  std::vector<int> saved_segments;    // per orbit: a saved start's shooting segments, else 0
  // Per [[equilibria]] entry: its branch's problem (start, values, window) and its start's name.
  std::vector<EquilibriumProblem> equilibria;
  std::vector<std::string> equilibria_starts;
  nlohmann::json marks;  // the marked parameter sets, in the map's plane or not
  std::string json_path;
  std::vector<MapOrbitResult> results;                  // per orbit, after run_map
  std::vector<MapEquilibriaResult> equilibria_results;  // per [[equilibria]] entry, after run_map
  // The jobs run_map runs: the orbits, then the equilibria entries.
  std::size_t jobs() const { return map.orbits.size() + map.equilibria.size(); }
};

// InputError for --jobs below 1, and for anything prepare_map checks, naming the map file's key.
MapRun prepare_map(const MapRequest& request);

// The orbits' branches, curves and grids and the equilibria entries' branches and curves on
// request.jobs threads; `stop` (may be null) asked between points; `callbacks`: a job (an orbit,
// then an equilibria entry: run.jobs() in all), a line per branch, curve or grid done. A job's
// failure is its result's `error`.
void run_map(MapRun& run, const std::atomic<bool>* stop, const JobCallbacks& callbacks);

// Writes the map's JSON (with `seconds`, the run's time) and a CSV per curve into request.out;
// returns the number of CSV files.
int write_map(const MapRun& run, double seconds);

}  // namespace sympathy::app
