// What the writers say of any system's orbit when the model knows nothing more (an equation case
// file's system): the amplitude of every state, half its range over one period. One plain
// integration of one period, sampled 800 times, at rtol 1e-9 (as MetronomeDescriber's).
#pragma once

#include <vector>

#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

class StateDescriber final : public OrbitDescriber {
 public:
  explicit StateDescriber(const OdeSystem& system) : system_(system) {}

  // Half the range of every state over one period (zeros when the period is not positive, the
  // integration's failure leaves them unknown: NaN).
  std::vector<double> amplitudes(const PeriodicOrbit& orbit) const;

  // "amplitudes" (amp_NAME per state).
  std::vector<Group> layout() const override;
  std::vector<double> describe(const PeriodicOrbit& orbit) const override {
    return amplitudes(orbit);
  }

 private:
  const OdeSystem& system_;
};

}  // namespace sympathy
