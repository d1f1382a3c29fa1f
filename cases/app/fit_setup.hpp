// sympathy fit as a request: a case's parameters fitted to a recording.
#pragma once

#include <atomic>
#include <cstdio>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "cases/app/case_arguments.hpp"
#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/core/trajectory_fit.hpp"

namespace sympathy::app {

// sympathy fit: the case (a metronome case file, or an equation case file
// compiled; behind pointers: the request's start points into it), the request and the engine's
// options read from them, every output checked (before any work).
struct FitSetup {
  std::unique_ptr<LoadedCase> c;               // a metronome case file ...
  std::unique_ptr<LoadedEquations> equations;  // ... or an equation case file
  std::string case_path, params;
  FitRequest request;
  TrajectoryFitOptions options;
  // The fit's model and problem (prepare_fit on the case's kind of model).
  PreparedFit prepare() const;
};
FitSetup fit_setup(const Arguments& args);
// Comma-separated names of a repeatable option (--free d,s --free c), in order; InputError for an
// empty name.
std::vector<std::string> names(const Arguments& args, const std::string& option);

}  // namespace sympathy::app
