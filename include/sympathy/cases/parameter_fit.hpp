// Fitting a case's parameters to a recording (sympathy fit): everything between the command
// line and the engine's trajectory fit (core/trajectory_fit.hpp). It builds the model (the full
// metronome model, or the platform alone with the pendula locked), reads and checks the
// recording against the model's state names, takes the initial state from the recording's first
// row (unrecorded states from a named start, else 0), and turns the free names into scaled,
// bounded unknowns. Every mistake is an InputError naming the file, line and column, or the
// option, and what was expected, found before any computation.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sympathy/cases/case_file.hpp"
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

struct PreparedFit {
  std::unique_ptr<OdeSystem> model;  // MetronomeModel or PlatformModel, at the case's values
  std::string model_description;     // e.g. "2 metronomes on a 1-D platform"
  Recording recording;
  TrajectoryFitProblem problem;
  std::vector<std::string> unknowns;        // "d", "s", "th1(0)", in the problem's order
  std::vector<std::string> initial_source;  // per state: "data", "--start NAME", "--initial",
                                            // "default" (0)
};

// Checks everything and sets the problem up; throws InputError.
PreparedFit prepare_fit(const CaseFile& file, const ModelSpec& spec, const FitRequest& request);

}  // namespace sympathy
