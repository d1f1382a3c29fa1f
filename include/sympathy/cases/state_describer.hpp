// What the writers say of any system's orbit when the model knows nothing more (an equation case
// file's system): the amplitude of every state, half its range over one period, its root mean
// square over the period, sqrt((1/T) integral of z_i^2 dt) (AUTO's L2 norm per state; at a torus
// bifurcation of the forced FitzHugh-Nagumo system it is known exactly), and its largest and
// smallest value over the period (AUTO's MAX U and MIN U). From the period's 801 samples
// (OrbitDescriber's sample_period); the mean square by the trapezoidal rule, which on a smooth
// periodic function converges faster than any power of the spacing h = T/800; each extreme by
// the parabola through the extreme sample and its two neighbours, whose error is O(h^3) of the
// state's third derivative there (on the Hopf normal form's circle, 2e-12 of the radius; the
// sample alone was 8e-6 off).
#pragma once

#include <vector>

#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

class StateDescriber final : public OrbitDescriber {
 public:
  explicit StateDescriber(const OdeSystem& system) : system_(system) {}

  struct Sizes {
    std::vector<double> amplitudes;      // half the range over one period
    std::vector<double> rms;             // the root mean square over one period
    std::vector<double> maxima, minima;  // the largest and smallest value over one period
  };
  // Every state's (zeros when the period is not positive; NaN when the integration fails).
  Sizes sizes(const PeriodicOrbit& orbit) const;

  // "amplitudes" (amp_NAME per state), "rms" (rms_NAME), "max" (max_NAME), "min" (min_NAME).
  std::vector<Group> layout() const override;
  std::vector<double> describe(const PeriodicOrbit& orbit) const override;

 private:
  const OdeSystem& system_;
};

}  // namespace sympathy
