// sympathy simulate as a request, below the command line and Python: a time series from a start
// of a case file of either kind (with --locked-pendula, the metronome case's platform alone), its
// samples streamed to --out's CSV and to a caller's hook, and a summary of where it ends
// (frequency, amplitudes and phase differences over the last 10 s at most).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "cases/app/arguments.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/oscillation.hpp"

namespace sympathy::app {

struct SimulationRun {
  // What is integrated: the system, its parameter values and start.
  std::shared_ptr<const OdeSystem> system;
  ParameterValues parameters;
  Eigen::VectorXd z0;
  FlowOptions flow;
  std::vector<double> times;  // the output samples, 0 .. t_end every dt
  double t_end = 0.0, dt = 0.0;
  // What the summary watches: `angles` the phase components (the first the frequency's
  // reference), `watched` the amplitude components; `directions` leading states are in metres
  // (the platform's) and the rest in rad, or -1 for no units (an equation case file).
  std::vector<int> angles, watched;
  int directions = 0;
  std::string case_path, params, start_name = "(--initial)", model_note;
  std::string out_path;  // --out's CSV ("" for none)

  // After run_simulation:
  OscillationSummary summary;
  FlowStatistics statistics;
  std::string note;          // a piecewise-smooth start where two solutions begin: which one
  std::string failure;       // the integration's error, where it stopped early
  bool interrupted = false;  // stopped by the caller's stop check
};

// The simulation `args` asks for, every check (the case, the start, the times, --out's path)
// made before any work.
SimulationRun prepare_simulation(const Arguments& args);

// Integrates: every output sample to --out's CSV (whole rows, also when stopped) and to
// `on_sample` if given; `stop_requested` (if given) asked after each sample. An integration
// error ends the run with what was computed kept (run.failure).
void run_simulation(SimulationRun& run, const std::function<bool()>& stop_requested,
                    const std::function<void(double, const Eigen::VectorXd&)>& on_sample = {});

}  // namespace sympathy::app
