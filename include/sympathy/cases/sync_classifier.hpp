// Which state a run of metronomes ended in, and when it got there: the classifier of a basin
// study (sympathy basins), from the pendulum angles sampled along a simulation.
//
// From upward zero crossings of each angle (linearly interpolated between samples; at 0.01 s
// sampling and 1.73 Hz the interpolation error is below 1e-3 rad of phase) the classifier forms,
// at every crossing of pendulum 1, each pendulum's phase difference to it: 2 pi times the time
// from that pendulum's nearest crossing, over the period just ended, in (-pi, pi] (positive: the
// pendulum leads). Over the last `window` seconds of the run (default 10 s, about 17 periods):
//   - stopped: a pendulum's amplitude (half its range) is below its stopped_amplitude (the basins
//     command gives the escapement's window start ths, 0.192 rad at Table I: below it the
//     pendulum no longer swings through the escapement's window);
//   - undetermined: fewer than three crossings of pendulum 1 (the run is too short to tell);
//   - not synchronized: a pendulum crosses zero more than once more or less often than pendulum 1
//     (no 1:1 frequency locking), or a phase difference strays more than lock_tolerance (0.1 rad)
//     from its mean over the window (quasi-periodic motion past a Neimark-Sacker point, a slow
//     drift);
//   - otherwise locked, named per group of pendula swinging along one direction (the row setup:
//     one group; the cross setup: the pairs {1,2} and {3,4}): a group is "in" when every member's
//     mean phase difference to its first member is within phase_tolerance (0.1 rad) of 0, "anti"
//     (a pair) when within phase_tolerance of pi. One group: in-phase or anti-phase; two groups:
//     in-in, anti-anti or in-anti (either pair in phase). Any other locked state: "locked" with
//     its mean phase differences to pendulum 1 rounded to multiples of pi/16, e.g. "locked+2.95"
//     (15 pi/16: one of the two orbits born at the row setup's anti-phase BP, k = 45 N/m).
// Time to synchronize: the first crossing of pendulum 1 after which the phase differences that
// define the state (each group's, against 0 or pi; a "locked" state's, against its means) stay
// within phase_tolerance to the end of the run; NaN for a state that is not locked.
//
// The two in-phase orbits of the row setup (the low-frequency one is stable for k of about 36 to
// 53 N/m) are both "in-phase": the result's frequency tells them apart.
#pragma once

#include <cmath>
#include <deque>
#include <span>
#include <string>
#include <vector>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy {

enum class SyncState {
  InPhase,
  AntiPhase,
  InIn,
  AntiAnti,
  InAnti,
  Locked,
  NotSynchronized,
  Stopped,
  Undetermined,
  Failed  // the simulation failed (set by the caller; the classifier never returns it)
};
// "in-phase", "anti-phase", "in-in", "anti-anti", "in-anti", "locked", "not-synchronized",
// "stopped", "undetermined", "failed".
std::string to_string(SyncState state);

struct SyncClassifierOptions {
  double window = 10.0;          // s, the end of the run the class is judged on
  double phase_tolerance = 0.1;  // rad, distance to 0 or pi of an in- or anti-phase pair
  double lock_tolerance = 0.1;   // rad, largest departure from its mean of a locked difference
  std::vector<double> stopped_amplitude;  // rad, per pendulum (empty: none is ever stopped)

  OptionCheck validate() const;
};

struct SyncResult {
  SyncState state = SyncState::Undetermined;
  std::string name;                       // to_string(state), or "locked+2.95" (phases to pi/16)
  double time_to_sync = std::nan("");     // s
  double frequency = std::nan("");        // Hz, pendulum 1's over the window
  std::vector<double> phase_differences;  // pendula 2..N to 1, means over the window, rad
  std::vector<double> amplitudes;         // per pendulum, over the window, rad
};

class SyncClassifier {
 public:
  // `groups`: the pendula (0-based) swinging along each direction, every pendulum in one group.
  // Throws std::invalid_argument for invalid options or groups.
  SyncClassifier(std::vector<std::vector<int>> groups, SyncClassifierOptions options);

  // One sample of the pendulum angles at time t (increasing).
  void add(double t, std::span<const double> angles);
  SyncResult classify() const;

 private:
  std::vector<std::vector<int>> groups_;
  SyncClassifierOptions options_;
  int pendula_ = 0;
  std::vector<std::vector<double>> crossings_;  // per pendulum, upward zero crossings
  std::deque<std::pair<double, std::vector<double>>> recent_;  // samples in the window
  double t_first_ = 0.0;
  bool started_ = false;
};

// The groups of a model's metronomes that swing along one direction (equal `angle`), in order.
std::vector<std::vector<int>> swing_groups(const ModelSpec& spec);

}  // namespace sympathy
