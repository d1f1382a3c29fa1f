#include "sympathy/continuation/orbit_describer.hpp"

#include "sympathy/core/flow.hpp"

namespace sympathy {

void sample_period(const OdeSystem& system, const PeriodicOrbit& orbit,
                   const std::function<void(double, const Eigen::VectorXd&)>& at) {
  const int samples = PeriodSamples::intervals;
  if (orbit.samples.of(orbit.state0, orbit.period)) {
    for (int k = 0; k <= samples; ++k) at(orbit.period * k / samples, orbit.samples.states.col(k));
    return;
  }
  FlowOptions o;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  Flow flow(system, o);
  std::vector<double> times;
  for (int k = 0; k <= samples; ++k) times.push_back(orbit.period * k / samples);
  flow.sample(orbit.state0, orbit.parameters, 0.0, times, at);
}

}  // namespace sympathy
