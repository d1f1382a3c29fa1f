#include "sympathy/cases/state_describer.hpp"

#include <cmath>

#include "sympathy/core/flow.hpp"

namespace sympathy {

std::vector<double> StateDescriber::amplitudes(const PeriodicOrbit& orbit) const {
  const int n = system_.dimension();
  std::vector<double> r(n, 0.0);
  if (!(orbit.period > 0.0)) return r;
  FlowOptions o;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  Flow flow(system_, o);
  const int samples = 800;
  std::vector<double> times;
  for (int k = 0; k <= samples; ++k) times.push_back(orbit.period * k / samples);
  Eigen::VectorXd lo = orbit.state0, hi = orbit.state0;
  try {
    flow.sample(orbit.state0, orbit.parameters, 0.0, times, [&](double, const Eigen::VectorXd& z) {
      lo = lo.cwiseMin(z);
      hi = hi.cwiseMax(z);
    });
  } catch (const IntegrationError&) {
    return std::vector<double>(n, std::nan(""));
  }
  for (int i = 0; i < n; ++i) r[i] = 0.5 * (hi[i] - lo[i]);
  return r;
}

std::vector<OrbitDescriber::Group> StateDescriber::layout() const {
  return {{"amplitudes", "amp_", system_.state_names()}};
}

}  // namespace sympathy
