// A recorded trajectory: samples of some state components of a system at increasing times, as
// read from a CSV file whose columns are `t` and state names (those of `sympathy simulate`).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

namespace sympathy {

struct Recording {
  std::string path;
  std::vector<double> times;         // strictly increasing
  std::vector<std::string> columns;  // recorded state names, in file order
  std::vector<int> components;       // their indices in the system's state
  Eigen::MatrixXd values;            // samples x columns
  std::vector<int> lines;            // line of each sample in the file

  int samples() const { return static_cast<int>(times.size()); }
};

// The largest magnitude of a recorded value: its square, summed over a recording, stays finite.
constexpr double kMaxRecordedMagnitude = 1e150;

// Reads a recording of a system with the given state names. Besides what read_csv rejects,
// throws InputError naming the file, line and column for: a first column other than `t`, a
// column that is not a state of the system (`system` describes it in the message), no state
// column at all, times that do not increase, and a value above kMaxRecordedMagnitude.

Recording read_recording(const std::string& path, const std::vector<std::string>& state_names,
                         const std::string& system = "the model");

}  // namespace sympathy
