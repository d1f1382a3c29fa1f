// Map files (cases/figures/map_*.toml): the orbits whose stability a two-parameter map shows,
// the two parameters with their windows, the grid that shades it and the case's parameter sets
// to mark. Read by `sympathy map` (cases/cli/map.cpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cases/app/case_loading.hpp"
#include "cases/app/saved_start.hpp"

namespace sympathy::app {

struct MapAxis {
  std::string parameter;
  double from = 0.0, to = 0.0;
  int points = 0;  // of the stability grid along it
};

struct MapOrbit {
  std::string name, start;
  std::optional<double> at;  // the branch found here and followed both ways (else from `from`)
  // `parent` and `from_point`: a point or event of a saved run as the start (its state, period,
  // segments and every parameter value: AUTO's IRS), instead of `start`.
  std::optional<SavedStart> saved;
};

// [[equilibria]]: a branch of equilibria in the first parameter (as `equilibria --start`), whose
// fold and Hopf points the map follows in both parameters (equilibrium_map.hpp).
struct MapEquilibria {
  std::string name, start;
  std::optional<double> at;  // the branch found here and followed both ways
  // `parent` and `from_point`: a saved equilibrium as the start (equilibria --parent F
  // --from-point P).
  std::optional<SavedStart> saved;
};

struct MapStudy {
  std::string path, name, title, case_path, params;
  // A metronome case's escapement instead of its file's (`escapement`); nullopt: the file's.
  std::optional<Escapement> escapement;
  Accuracy accuracy = Accuracy::Default;
  MapAxis first, second;
  std::vector<MapOrbit> orbits;
  std::vector<MapEquilibria> equilibria;
  std::vector<std::string> marks;  // parameter sets of the case, marked on the map
};

// Reads and checks a map file (keys, types, windows, names; not yet its case); throws
// InputError naming the file, the line and the key.
MapStudy load_map(const std::string& path);

}  // namespace sympathy::app
