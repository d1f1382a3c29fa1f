#include "sympathy/cases/state_describer.hpp"

#include <cmath>

#include "sympathy/core/flow.hpp"

namespace sympathy {

std::vector<double> StateDescriber::amplitudes(const PeriodicOrbit& orbit) const {
  const int n = system_.dimension();
  std::vector<double> r(n, 0.0);
  if (!(orbit.period > 0.0)) return r;
  Eigen::VectorXd lo = orbit.state0, hi = orbit.state0;
  try {
    sample_period(system_, orbit, [&](double, const Eigen::VectorXd& z) {
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
