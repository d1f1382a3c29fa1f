#include "sympathy/continuation/orbit_describer.hpp"

#include <cmath>

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

double sampled_extreme(const Eigen::VectorXd& y, bool largest) {
  const long last = y.size() - 1;
  const bool periodic =
      y[last] == y[0] || std::abs(y[last] - y[0]) <= 1e-9 * y.cwiseAbs().maxCoeff();
  const long m = periodic ? last : y.size();  // the distinct samples
  long k = 0;
  for (long j = 1; j < m; ++j)
    if (largest ? y[j] > y[k] : y[j] < y[k]) k = j;
  if (m < 3 || (!periodic && (k == 0 || k == last))) return y[k];
  const double before = y[(k + m - 1) % m], at = y[k], after = y[(k + 1) % m];
  const double curvature = after - 2.0 * at + before;
  if (curvature == 0.0) return at;
  return at - (after - before) * (after - before) / (8.0 * curvature);
}

double orbit_extreme(const OdeSystem& system, const PeriodicOrbit& orbit, int state, bool largest) {
  Eigen::VectorXd y(PeriodSamples::intervals + 1);
  int count = 0;
  sample_period(system, orbit, [&](double, const Eigen::VectorXd& z) {
    if (count < y.size()) y[count++] = z[state];
  });
  return sampled_extreme(y.head(count), largest);
}

}  // namespace sympathy
