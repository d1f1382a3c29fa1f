// Frequency, amplitudes and phase differences of oscillating state components, from a sampled
// trajectory fed sample by sample (nothing is stored but the crossings and a trailing window).
//
// Phases come from upward zero crossings (linearly interpolated between samples) of each
// watched component; the frequency from the reference component's crossings; amplitudes are
// half the peak-to-peak range over the trailing window.
#pragma once

#include <deque>
#include <vector>

#include <Eigen/Dense>

namespace sympathy {

struct OscillationSummary {
  double frequency = 0.0;                 // Hz, of the reference component; 0 if undetermined
  std::vector<double> amplitudes;         // per component, over the trailing window
  std::vector<double> phase_differences;  // rad in (-pi, pi], component minus the reference
  int cycles = 0;                         // reference crossings inside the window
};

class OscillationAnalyzer {
 public:
  // `phase_components`: components whose phases are compared (the first is the reference);
  // `amplitude_components`: components whose amplitudes are reported; `window`: trailing time.
  OscillationAnalyzer(std::vector<int> phase_components, std::vector<int> amplitude_components,
                      double window);

  void add(double t, const Eigen::VectorXd& z);
  OscillationSummary summary() const;

 private:
  std::vector<int> phase_components_;
  std::vector<int> amplitude_components_;
  double window_;
  bool has_previous_ = false;
  double t_previous_ = 0.0;
  Eigen::VectorXd z_previous_;
  std::vector<std::vector<double>> crossings_;  // per phase component, upward zero crossings
  std::deque<std::pair<double, Eigen::VectorXd>> recent_;
};

}  // namespace sympathy
