// Fitting a case's parameters to a recording (sympathy fit): everything between the command
// line and the engine's trajectory fit (core/trajectory_fit.hpp). The model is the case's system:
// for a metronome case file the full metronome model or the platform alone with the pendula
// locked, for an equation case file its compiled system (FitModel says which parameters are
// positive, their bounds, the default start). It reads and checks the recording against the
// model's state names, takes the initial state from the recording's first row (unrecorded states
// from a named start, else the model's default), and turns the free names into scaled, bounded
// unknowns. Every mistake is an InputError naming the file, line and column, or the option, and
// what was expected, found before any computation.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/core/recording.hpp"
#include "sympathy/core/trajectory_fit.hpp"

namespace sympathy {

// An interval LO:HI given to an unknown with --range NAME=LO:HI.
struct Range {
  std::string name;
  double lower = 0.0;
  double upper = 0.0;
  std::string source;  // "--range d=1e-6:1e-5"
};
// Parses "NAME=LO:HI" given to `option`; throws InputError naming the option.
Range parse_range(const std::string& text, const std::string& option);

struct FitRequest {
  std::string data;                       // the recording (CSV)
  std::vector<std::string> free;          // parameter names
  std::vector<std::string> free_initial;  // state names whose initial value is fitted too
  bool locked_pendula = false;
  const StartSpec* start = nullptr;  // unrecorded states start here (else 0) ...
  std::vector<Assignment> initial;   // ... with these on top
  std::vector<Assignment> sigma;     // noise level (residual scale) of a recorded column
  std::vector<Range> ranges;         // bounds and global search box of unknowns
  double search_factor = 10.0;       // default box of a positive parameter: start / f .. start * f
};

// How a fitted parameter may vary. A positive one is searched on a logarithmic scale (the global
// box start / f .. start * f); a signed one linearly, in units of `scale`, the global box
// start +- `half_width`. Both within [lower, upper].
struct ParameterDomain {
  bool positive = true;
  double scale = 1.0, half_width = 1.0;  // signed only
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

// The system a fit adjusts, at the case's parameter values.
struct FitModel {
  std::unique_ptr<OdeSystem> owned;  // the system when the fit owns it (the metronome models)
  const OdeSystem* system = nullptr;
  std::string description;  // "2 metronomes on a 1-D platform", "the equations of FILE"
  std::string case_path;
  ParameterValues values;      // the case's, with --params and --set
  Eigen::VectorXd initial;     // unrecorded states' default start ...
  std::string initial_source;  // ... and what to call it: "default" (0), "[states]"
  // The domain of a parameter of `system` whose starting value is `start`.
  std::function<ParameterDomain(const std::string& name, double start)> domain;
  // For a name that is not a parameter of `system`: why, if the model knows ("" otherwise).
  std::function<std::string(const std::string& name)> why_not_a_parameter;
};

// A metronome case file's model: MetronomeModel, or PlatformModel with the pendula locked. Its
// parameters are positive but for the directions (angleN, in degrees); states start at 0.
FitModel metronome_fit_model(const CaseFile& file, const ModelSpec& spec, bool locked_pendula);

// An equation case file's model: its compiled `system` at `values`. A parameter is positive
// where the file bounds it below by min >= 0 and it starts above 0; else signed, in units of its
// start's size (1 if it starts at 0), the global box 10 such units either side. The file's min
// and max bound it. Unrecorded states start at the file's [states].
FitModel equation_fit_model(const EquationCase& file, const OdeSystem& system,
                            const ParameterValues& values);

struct PreparedFit {
  std::unique_ptr<OdeSystem> owned;  // the model's system when the fit owns it
  const OdeSystem* model = nullptr;  // the system fitted, at the case's values
  std::string model_description;     // e.g. "2 metronomes on a 1-D platform"
  Recording recording;
  TrajectoryFitProblem problem;
  std::vector<std::string> unknowns;        // "d", "s", "th1(0)", in the problem's order
  std::vector<std::string> initial_source;  // per state: "data", "--start NAME", "--initial",
                                            // "default" (0)
};

// Checks everything and sets the problem up; throws InputError.
PreparedFit prepare_fit(FitModel model, const FitRequest& request);
// The same for a metronome case file (request.locked_pendula chooses the model).
PreparedFit prepare_fit(const CaseFile& file, const ModelSpec& spec, const FitRequest& request);

}  // namespace sympathy
