#include "sympathy/cases/state_describer.hpp"

#include <algorithm>
#include <cmath>

#include "sympathy/core/flow.hpp"

namespace sympathy {

StateDescriber::Sizes StateDescriber::sizes(const PeriodicOrbit& orbit) const {
  const int n = system_.dimension();
  const std::vector<double> zeros(n, 0.0), unknown(n, std::nan(""));
  if (!(orbit.period > 0.0)) return {zeros, zeros, zeros, zeros};
  // One period's samples, equally spaced, both ends.
  Eigen::MatrixXd samples(n, PeriodSamples::intervals + 1);
  int count = 0;
  Eigen::VectorXd integral = Eigen::VectorXd::Zero(n), previous_square;
  double previous_t = 0.0;
  try {
    sample_period(system_, orbit, [&](double t, const Eigen::VectorXd& z) {
      if (count < samples.cols()) samples.col(count++) = z;
      const Eigen::VectorXd square = z.cwiseAbs2();
      if (previous_square.size() == n)
        integral += 0.5 * (t - previous_t) * (square + previous_square);
      previous_square = square;
      previous_t = t;
    });
  } catch (const IntegrationError&) {
    return {unknown, unknown, unknown, unknown};
  }
  Sizes r{zeros, zeros, zeros, zeros};
  const OrbitExtremes extremes = refined_extremes(system_, orbit, samples.leftCols(count));
  for (int i = 0; i < n; ++i) {
    const Eigen::VectorXd y = samples.row(i).head(count).transpose();
    r.maxima[i] = extremes.maxima[i];
    r.minima[i] = extremes.minima[i];
    r.amplitudes[i] = 0.5 * (y.maxCoeff() - y.minCoeff());
    r.rms[i] = std::sqrt(integral[i] / orbit.period);
  }
  return r;
}

std::vector<double> StateDescriber::describe(const PeriodicOrbit& orbit) const {
  Sizes s = sizes(orbit);
  std::vector<double> all = std::move(s.amplitudes);
  for (const auto* group : {&s.rms, &s.maxima, &s.minima})
    all.insert(all.end(), group->begin(), group->end());
  return all;
}

std::vector<OrbitDescriber::Group> StateDescriber::layout() const {
  const auto names = system_.state_names();
  return {{"amplitudes", "amp_", names},
          {"rms", "rms_", names},
          {"max", "max_", names},
          {"min", "min_", names}};
}

}  // namespace sympathy
