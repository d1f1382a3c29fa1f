#include "sympathy/continuation/orbit_describer.hpp"

#include "sympathy/core/flow.hpp"

namespace sympathy {

void sample_period(const OdeSystem& system, const PeriodicOrbit& orbit,
                   const std::function<void(double, const Eigen::VectorXd&)>& at) {
  FlowOptions o;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  Flow flow(system, o);
  const int samples = 800;
  std::vector<double> times;
  for (int k = 0; k <= samples; ++k) times.push_back(orbit.period * k / samples);
  flow.sample(orbit.state0, orbit.parameters, 0.0, times, at);
}

}  // namespace sympathy
