#include "sympathy/cases/state_describer.hpp"

#include <cmath>

#include "sympathy/core/flow.hpp"

namespace sympathy {

StateDescriber::Sizes StateDescriber::sizes(const PeriodicOrbit& orbit) const {
  const int n = system_.dimension();
  Sizes r{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  if (!(orbit.period > 0.0)) return r;
  Eigen::VectorXd lo = orbit.state0, hi = orbit.state0;
  Eigen::VectorXd integral = Eigen::VectorXd::Zero(n), previous_square;
  double previous_t = 0.0;
  try {
    sample_period(system_, orbit, [&](double t, const Eigen::VectorXd& z) {
      lo = lo.cwiseMin(z);
      hi = hi.cwiseMax(z);
      const Eigen::VectorXd square = z.cwiseAbs2();
      if (previous_square.size() == n)
        integral += 0.5 * (t - previous_t) * (square + previous_square);
      previous_square = square;
      previous_t = t;
    });
  } catch (const IntegrationError&) {
    return {std::vector<double>(n, std::nan("")), std::vector<double>(n, std::nan(""))};
  }
  for (int i = 0; i < n; ++i) {
    r.amplitudes[i] = 0.5 * (hi[i] - lo[i]);
    r.rms[i] = std::sqrt(integral[i] / orbit.period);
  }
  return r;
}

std::vector<double> StateDescriber::describe(const PeriodicOrbit& orbit) const {
  Sizes s = sizes(orbit);
  s.amplitudes.insert(s.amplitudes.end(), s.rms.begin(), s.rms.end());
  return s.amplitudes;
}

std::vector<OrbitDescriber::Group> StateDescriber::layout() const {
  return {{"amplitudes", "amp_", system_.state_names()}, {"rms", "rms_", system_.state_names()}};
}

}  // namespace sympathy
