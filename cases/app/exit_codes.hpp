// The program's exit codes, one table (docs/reference/exit-codes.md says what each prints): what
// a run's outcome means to a script. Bad input (2) is told from a numerical outcome (4, 7) so that
// a script can tell "fix the call" from "the computation did not get there".
#pragma once

#include "sympathy/continuation/driver.hpp"

namespace sympathy::app {

constexpr int kDone = 0;
constexpr int kFailure = 1;            // anything else (e.g. the compiler failing on a system)
constexpr int kBadInput = 2;           // nothing computed: the message names file, key or option
constexpr int kIntegrationFailed = 3;  // the integrator gave up (a simulation keeps its CSV)
constexpr int kNumericalFailure = 4;   // no start, Newton or a fit did not converge
constexpr int kOutputFailed = 5;       // an output could not be written
constexpr int kInterrupted = 6;        // SIGINT, SIGTERM or SIGHUP: complete files up to there
constexpr int kStoppedShort = 7;       // a branch or curve ended before its bound for a
                                       // numerical reason (the step fell below its minimum):
                                       // what it computed is written

// What a continuation's stop means for the exit code: the window's edge, the point limit asked
// for, a Hopf end, a homoclinic end, a closed curve, a grazing of hybrid orbits or a family that
// turned back are ends (0); the
// minimum step is a numerical failure short of the bound (kStoppedShort).
constexpr int exit_code(StopReason stop) {
  switch (stop) {
    case StopReason::MinimumStep:
      return kStoppedShort;
    case StopReason::Interrupted:
      return kInterrupted;
    case StopReason::StartFailed:
      return kNumericalFailure;
    case StopReason::ParameterBound:
    case StopReason::PointLimit:
    case StopReason::TurnedBack:
    case StopReason::HopfPoint:
    case StopReason::Homoclinic:
    case StopReason::Closed:
    case StopReason::UserValue:
    case StopReason::Nonsmooth:
      return kDone;
  }
  return kFailure;
}

// Two runs' codes as one (a study's branches): interruption first, then a failure to start,
// then a run stopped short, then done.
constexpr int worse(int a, int b) {
  const auto rank = [](int code) {
    return code == kInterrupted ? 3 : code == kNumericalFailure ? 2 : code == kStoppedShort ? 1 : 0;
  };
  return rank(b) > rank(a) ? b : a;
}

// A run's code (a branch, a curve, equilibria): its stop, and a two-way run's backward stop.
template <class Run>
constexpr int exit_code_of(const Run& run) {
  int code = exit_code(run.stop);
  if constexpr (requires { run.backward_stop; })
    if (run.backward_stop) code = worse(code, exit_code(*run.backward_stop));
  return code;
}

}  // namespace sympathy::app
