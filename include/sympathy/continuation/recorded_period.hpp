// An orbit started from data: one recorded or simulated period (AUTO's `dat` files), a CSV of a
// time column `t` and one column per state, named by the system's states (what `sympathy
// simulate --out` writes). Its first row is the start z0; the period guess is its time span, or,
// where the recording runs on past one period, its first return to the section through z0. Newton
// (solve_periodic_orbit) then starts there, with no transient: a recorded orbit may be unstable.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

struct RecordedPeriod {
  std::string path;
  Eigen::VectorXd state0;  // the first row, in the system's state order
  double start_time = 0.0;
  double period = 0.0;    // the guess: the first return, or the span
  double span = 0.0;      // last time - first time
  bool returned = false;  // period is a first return found inside the data (else the span)
  int return_line = 0;    // the line of the first row past the return (0 if none)
  int rows = 0;
  double scaled_by = 0.0;  // > 0: its time was scaled to [0, 1] and multiplied by this (AUTO's dat)
};

// At least this many rows: fewer cannot show a closed curve (two rows are a chord, three a
// triangle at best); a period written by `simulate` at its default --dt has hundreds.
inline constexpr int kMinimumPeriodRows = 4;

// Reads and checks `path`, before any integration: on top of what read_recording rejects (a
// first column other than t, a column that is not a state, times that do not increase), an
// InputError naming the file, the line and the column for a state without a column, fewer than
// kMinimumPeriodRows rows, a state that does not move between the first two rows, and a recording
// that neither returns to its first row's section nor closes (its last row more than two of its
// largest steps between rows away from the first: less than one period). `system` describes the
// system in messages ("cases/examples/lcbp.toml"). `angles`: the states that are angles
// (OdeSystem::angle_states), compared on the circle: a rotation that gains 2 pi is back.
RecordedPeriod read_recorded_period(const std::string& path,
                                    const std::vector<std::string>& state_names,
                                    const std::string& system = "the system",
                                    const std::vector<int>& angles = {});

// Newton from the recording's first row and period guess (solve_periodic_orbit), at parameter
// values p, the iterates kept in `subspace`. Throws std::invalid_argument for a state of the
// wrong size and for a periodically forced system (its period is the forcing's, not the data's:
// solve_periodic_orbit with it).
PeriodicOrbit orbit_from_recorded_period(const OdeSystem& system, const ParameterValues& p,
                                         const RecordedPeriod& recorded,
                                         const InvariantSubspace& subspace,
                                         const OrbitOptions& options);

}  // namespace sympathy
