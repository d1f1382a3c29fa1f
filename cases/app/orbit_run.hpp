// sympathy orbit as a request, below the command line and Python: one periodic orbit from a named
// start (or a recorded period) of a case file of either kind, with its Floquet multipliers and
// what the case's describer says of it (a metronome case's amplitudes and phase differences, an
// equation case's amplitudes and RMS per state); its JSON written to --json.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/app/arguments.hpp"
#include "cases/app/loaded_system.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy::app {

struct OrbitRun {
  std::unique_ptr<LoadedSystem> c;  // the case, of either kind
  std::string start_name;           // for a report: the start's name, or the recording described
  OrbitOptions options;
  PeriodicOrbit orbit;
  std::vector<double> amplitudes, phase_differences, rms;  // per state (rms: equation cases)
  double seconds = 0.0;                                    // loading and Newton
  nlohmann::json json;  // the orbit's JSON with the case, its set, the start and the run time
};

// The orbit `args` asks for: every check (the case, the start, --json's path) before any work,
// then the orbit; its JSON written to --json if given. Throws InputError, OutputError.
OrbitRun run_orbit(const Arguments& args);

// How an orbit was integrated, for a report: the flow's options as run (BDF where the measured
// stiffness switched to it), what the method ran on (" (dense linear solver)", an explicit
// table's name), and the number of states integrated (a symmetry reduction's).
struct IntegrationAsRun {
  FlowOptions flow;
  std::string solver;
  int integrated_dimension = 0;
};
IntegrationAsRun integration_as_run(const OdeSystem& model, const PeriodicOrbit& orbit,
                                    const OrbitOptions& options);

}  // namespace sympathy::app
