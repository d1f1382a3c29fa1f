// What the writers say of a metronome model's orbit beyond the engine's figures: the amplitude of
// every position (half its range over one period) and each pendulum's phase difference to the
// first (from upward zero crossings, rad in (-pi, pi]; NaN for a pendulum that does not cross
// zero). One plain integration of one period, sampled 800 times, at rtol 1e-9.
#pragma once

#include <vector>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/orbit_describer.hpp"

namespace sympathy {

class MetronomeDescriber final : public OrbitDescriber {
 public:
  explicit MetronomeDescriber(const MetronomeModel& model) : model_(model) {}

  struct Report {
    std::vector<double> amplitudes;         // per position (platform and angles)
    std::vector<double> phase_differences;  // th2 .. thN to th1
  };
  Report report(const PeriodicOrbit& orbit) const;

  // "amplitudes" (amp_x, amp_th1, ...) and "phase_differences" (phase_th2, ...).
  std::vector<Group> layout() const override;
  std::vector<double> describe(const PeriodicOrbit& orbit) const override;

 private:
  const MetronomeModel& model_;
};

}  // namespace sympathy
