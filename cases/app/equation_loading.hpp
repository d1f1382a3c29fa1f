// Equation case files (kind = "equations") loaded for a request: the file, the parameter values of
// its set and overrides, a recorded period to start from (read and checked against the file's
// states before anything is compiled), and its system compiled or taken from the cache
// (equation_compiler.hpp).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/equation_compiler.hpp"
#include "sympathy/continuation/recorded_period.hpp"

namespace sympathy::app {

struct LoadedEquations {
  EquationCase file;
  std::string params;  // the parameter set applied ("" if none)
  ParameterValues values;
  EquationBuild build;
  std::optional<RecordedPeriod> start_data;  // a recorded period to start from, if given
};

// The file at `path`, parameter set `params` ("" for the file's default) and `sets` on top, and
// the recorded period at `start_data` if given (checked against the file's states and angles
// before anything is compiled); its system compiled or from the cache.
LoadedEquations load_equations(const std::string& path, const std::string& params,
                               const std::vector<Assignment>& sets,
                               const std::optional<std::string>& start_data = std::nullopt);

// InputError unless the file's orbits have a known period: an autonomous system, or a forced one
// (its equations use t) that declares forcing_period (positive at its values).
void check_period_known(const LoadedEquations& e);
// InputError for a forced system: `what` (a command or option) is for autonomous systems only.
void check_autonomous(const LoadedEquations& e, const std::string& what);
// InputError unless `system` is autonomous where a recorded period is the start: a forced
// system's period is the forcing's, not the recording's.
void check_start_data_system(const std::optional<RecordedPeriod>& recorded, const OdeSystem& system,
                             const std::string& case_path);

// "system compiled in 1.23 s against the headers in DIR (CACHE/KEY.so)" or "system from the
// cache (CACHE/KEY.so)", with why an entry present was rebuilt.
std::string describe_build(const EquationBuild& build);

}  // namespace sympathy::app
