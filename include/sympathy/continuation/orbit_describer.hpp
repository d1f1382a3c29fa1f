// What only a model knows about its orbits, for the writers: named numbers per orbit (a
// metronome model's amplitudes and the pendula's phase differences). The engine and the writers
// know nothing about metronomes; a model that wants columns of its own implements this, and the
// branch run describes each point once, as it is found.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

class OrbitDescriber {
 public:
  // A group of numbers: JSON gets `name` (a list per branch point; an object of `labels` for an
  // orbit), CSV gets one column `csv_prefix + label` per number.
  struct Group {
    std::string name;                 // "amplitudes"
    std::string csv_prefix;           // "amp_"
    std::vector<std::string> labels;  // "x", "th1", ...
  };

  virtual ~OrbitDescriber() = default;
  virtual std::vector<Group> layout() const = 0;
  // The numbers of every group, in layout order (NaN where a number is unknown). Called from
  // several threads at once when branches run side by side.
  virtual std::vector<double> describe(const PeriodicOrbit& orbit) const = 0;
};

// One period of `orbit` sampled 801 times (both ends included): what describers take amplitudes
// and phases from (the samples' spacing, T / 800, bounds the error of an interpolated zero
// crossing well below a describer's digits). The orbit's own samples where it carries them (the
// run with sensitivities that confirmed it, at the shooting flow's tolerance with its
// sensitivities in the error test), else a plain flow at rtol 1e-11, atol 1e-14; the two agree
// to about 1e-9 relative (tests/continuation/period_samples_test.cpp). Throws IntegrationError
// where the period cannot be integrated.
void sample_period(const OdeSystem& system, const PeriodicOrbit& orbit,
                   const std::function<void(double, const Eigen::VectorXd&)>& at);

// The extreme of the samples y over one period (equally spaced, both ends) that `largest` asks
// for, refined by the parabola through the extreme sample and its neighbours (the vertex lies
// within half a spacing of that sample). A state that comes back to itself wraps around (its
// last sample is its first); one that gains over the period (an angle that rotates: AUTO's pen)
// has its extreme at an end or inside, refined only inside.
// The parabola's error is O(h^3) of the state's third derivative there (on the Hopf normal
// form's circle, 2e-12 of the radius, where the extreme sample alone was 8e-6 off).
double sampled_extreme(const Eigen::VectorXd& y, bool largest);
// Every state's largest and smallest value over `orbit`, from `samples` (n x (intervals + 1), one
// period as sample_period gives it) refined on the flow: the time where the state's derivative
// vanishes, by Newton from the sample before, each iterate integrated at rtol 1e-12. The
// parabola above was 2.7e-7 off (5e-7 relative) at the spike of AUTO's pp2 (T = 36 on 800
// samples) and 1e-5 relative on lor; these are within 1e-9 there of SciPy's DOP853 at rtol
// 1e-13. The parabola's value where the system has no Jacobian, the extreme is at an end, or
// Newton leaves the two spacings around the sample.
struct OrbitExtremes {
  Eigen::VectorXd maxima, minima;
};
OrbitExtremes refined_extremes(const OdeSystem& system, const PeriodicOrbit& orbit,
                               const Eigen::MatrixXd& samples);
// A state's largest (or smallest) value over the orbit's period, from sample_period, refined.
double orbit_extreme(const OdeSystem& system, const PeriodicOrbit& orbit, int state, bool largest);

}  // namespace sympathy
