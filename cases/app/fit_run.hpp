// sympathy fit as a request, below the command line and Python: a case's parameters (and initial
// states) fitted to a recorded time series by least squares, and its outputs: the fitted model at
// the data's times (--csv), the case file with the fitted values (--out, metronome case files) and
// the JSON (--json).
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
  std::vector<Assignment> sets;  // --set, recorded in a fitted case file
  FitRequest request;
  TrajectoryFitOptions options;
  // The fit's model and problem (prepare_fit on the case's kind of model).
  PreparedFit prepare() const;
};
FitSetup fit_setup(const Arguments& args);
// Comma-separated names of a repeatable option (--free d,s --free c), in order; InputError for an
// empty name.
std::vector<std::string> names(const Arguments& args, const std::string& option);

struct FitRun {
  PreparedFit fit;
  TrajectoryFitResult result;
  bool determined() const { return result.undetermined.empty(); }
  // The free parameters' count (the unknowns after them are initial states).
  int parameter_count() const { return static_cast<int>(fit.problem.parameters.size()); }
  // The start of the fitted trajectory: the problem's initial state with the fitted initial
  // values set.
  Eigen::VectorXd fitted_initial_state() const;
};
// The fit (the engine's fit_trajectory on the prepared problem); `stop_requested` (may be empty)
// asked before each integration ends it at the best point so far (TrajectoryFitOptions).
FitRun run_fit(const FitSetup& setup, std::function<bool()> stop_requested = {});

// The share of the data's variation (scaled columns about their means) the fit explains: 1 -
// RSS / total; below 0.9 a local minimum is likely.
double explained_variation(const FitRun& run);

// The fitted model at the data's times, as CSV (t and every state).
void write_fitted_series(const std::string& path, const FitSetup& setup, const FitRun& run);

// A metronome case file with the fitted values in its parameter set (and --set's values not
// fitted), each commented with where it came from; returns the edits made. Only for a fit that
// converged and determined every unknown (the caller says why not otherwise).
std::vector<std::string> write_fitted_case(const std::string& path, const FitSetup& setup,
                                           const FitRun& run);

// The fit's JSON: the data, the model, the unknowns with their errors, covariance and correlation,
// the residuals, the stages, the integrator; `csv` and `out` the files written ("" for none).
void write_fit_json(const std::string& path, const FitSetup& setup, const FitRun& run,
                    const std::string& csv, const std::string& out, double seconds);

}  // namespace sympathy::app
