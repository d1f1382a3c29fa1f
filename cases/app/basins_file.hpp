// Basins study files (cases/figures/basins_*.toml): a basin study written down beside the figure
// studies, so that the figure in the README is one command (`sympathy basins FILE`). Read by
// `sympathy basins` (cases/cli/basins.cpp) when its file has a top-level `case` key.
#pragma once

#include <string>
#include <vector>

#include "sympathy/cases/basin_study.hpp"
#include "sympathy/cases/case_file.hpp"

namespace sympathy::app {

struct BasinsFile {
  std::string path, title, case_path, params;
  std::vector<Assignment> sets;     // on top of the parameter set
  std::vector<Assignment> initial;  // state values every start shares
  BasinOptions options;             // grid, starts, angles, seed, t_end, dt, classifier
};

// Whether `path` is a basins study file (a TOML file with a top-level `case` key) rather than a
// case file. False for a file that cannot be read or parsed (the case file reader reports it).
bool is_basins_file(const std::string& path);

// Reads and checks a basins study file (keys, types, and BasinOptions::validate with each field
// named by its key: "FILE:LINE: grid[1].count: expected at least one value"); not yet its case.
// Throws InputError naming the file, the line and the key.
BasinsFile load_basins_file(const std::string& path);

}  // namespace sympathy::app
