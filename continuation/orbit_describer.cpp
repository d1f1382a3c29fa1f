#include "sympathy/continuation/orbit_describer.hpp"

#include <algorithm>
#include <cmath>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy {

void sample_period(const OdeSystem& system, const PeriodicOrbit& orbit,
                   const std::function<void(double, const Eigen::VectorXd&)>& at) {
  const int samples = PeriodSamples::intervals;
  if (orbit.samples.of(orbit.state0, orbit.period)) {
    for (int k = 0; k <= samples; ++k) at(orbit.period * k / samples, orbit.samples.states.col(k));
    return;
  }
  // rtol 1e-11: at 1e-9 the maximum of AUTO's pp2's spike (T = 36) was 2e-8 off (relative).
  FlowOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-14;
  Flow flow(system, o);
  std::vector<double> times;
  for (int k = 0; k <= samples; ++k) times.push_back(orbit.period * k / samples);
  flow.sample(orbit.state0, orbit.parameters, 0.0, times, at);
}

namespace {

// The sample at the extreme of y that `largest` asks for, and whether it lies inside (a state
// that gains over the period, an angle that rotates, may have it at an end: no vertex there).
struct ExtremeSample {
  long k = 0;
  long m = 0;  // the distinct samples (the last is the first where the state comes back)
  bool inside = false;
};

ExtremeSample extreme_sample(const Eigen::VectorXd& y, bool largest) {
  const long last = y.size() - 1;
  const bool periodic =
      y[last] == y[0] || std::abs(y[last] - y[0]) <= 1e-9 * y.cwiseAbs().maxCoeff();
  ExtremeSample e;
  e.m = periodic ? last : y.size();
  for (long j = 1; j < e.m; ++j)
    if (largest ? y[j] > y[e.k] : y[j] < y[e.k]) e.k = j;
  e.inside = e.m >= 3 && (periodic || (e.k != 0 && e.k != last));
  return e;
}

// The parabola's vertex through the extreme sample and its neighbours, as an offset from the
// sample in spacings (within a half).
double vertex_offset(const Eigen::VectorXd& y, const ExtremeSample& e) {
  const double before = y[(e.k + e.m - 1) % e.m], at = y[e.k], after = y[(e.k + 1) % e.m];
  const double curvature = after - 2.0 * at + before;
  return curvature == 0.0 ? 0.0 : (before - after) / (2.0 * curvature);
}

}  // namespace

double sampled_extreme(const Eigen::VectorXd& y, bool largest) {
  const ExtremeSample e = extreme_sample(y, largest);
  if (!e.inside) return y[e.k];
  const double before = y[(e.k + e.m - 1) % e.m], at = y[e.k], after = y[(e.k + 1) % e.m];
  const double curvature = after - 2.0 * at + before;
  if (curvature == 0.0) return at;
  return at - (after - before) * (after - before) / (8.0 * curvature);
}

namespace {

// One state's extreme refined on `flow` (at rtol 1e-12): Newton in time on the state's
// derivative f_i (zero at the extreme; its rate of change is row i of J f), each iterate
// integrated from the sample before the extreme one, at most two spacings.
double refine(Flow& flow, const PeriodicOrbit& orbit, const Eigen::MatrixXd& samples, int state,
              bool largest) {
  const OdeSystem& system = flow.system();
  const Eigen::VectorXd y = samples.row(state).transpose();
  const double parabola = sampled_extreme(y, largest);
  const ExtremeSample e = extreme_sample(y, largest);
  if (!e.inside || !system.differentiable() || samples.cols() < 3) return parabola;
  const int n = system.dimension();
  const double h = orbit.period / static_cast<double>(samples.cols() - 1);
  const long base = (e.k + e.m - 1) % e.m;
  const double t0 = h * static_cast<double>(base);
  double span = h * (1.0 + vertex_offset(y, e));
  try {
    const Eigen::VectorXd z0 = samples.col(base);
    Eigen::VectorXd z = z0, f(n);
    Eigen::MatrixXd jac(n, n);
    for (int iteration = 0; iteration < 8; ++iteration) {
      if (!(span > 0.0 && span < 2.0 * h)) return parabola;
      z = flow.advance(z0, orbit.parameters, t0, t0 + span);
      system.rhs(t0 + span, z.data(), orbit.parameters.data(), f.data());
      system.jacobian(t0 + span, z.data(), orbit.parameters.data(), jac);
      const double rate = jac.row(state).dot(f);
      if (rate == 0.0 || (largest ? rate > 0.0 : rate < 0.0)) return parabola;
      const double step = f[state] / rate;
      span -= step;
      if (std::abs(step) <= 1e-13 * orbit.period) {
        z = flow.advance(z0, orbit.parameters, t0, t0 + span);
        break;
      }
    }
    // Newton's point is the extreme only where it is at least as far out as every sample.
    const double value = z[state];
    return (largest ? value >= y[e.k] : value <= y[e.k]) ? value : parabola;
  } catch (const IntegrationError&) {
    return parabola;
  }
}

FlowOptions refining_flow(const Eigen::MatrixXd& samples) {
  FlowOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-14 * std::max(1.0, samples.cwiseAbs().maxCoeff());
  return o;
}

}  // namespace

OrbitExtremes refined_extremes(const OdeSystem& system, const PeriodicOrbit& orbit,
                               const Eigen::MatrixXd& samples) {
  const int n = static_cast<int>(samples.rows());
  OrbitExtremes r{Eigen::VectorXd(n), Eigen::VectorXd(n)};
  Flow flow(system, refining_flow(samples));  // one for every state's (a flow is set up once)
  for (int i = 0; i < n; ++i) {
    r.maxima[i] = refine(flow, orbit, samples, i, true);
    r.minima[i] = refine(flow, orbit, samples, i, false);
  }
  return r;
}

double orbit_extreme(const OdeSystem& system, const PeriodicOrbit& orbit, int state, bool largest) {
  Eigen::MatrixXd samples(system.dimension(), PeriodSamples::intervals + 1);
  int count = 0;
  sample_period(system, orbit, [&](double, const Eigen::VectorXd& z) {
    if (count < samples.cols()) samples.col(count++) = z;
  });
  const Eigen::MatrixXd taken = samples.leftCols(count);
  Flow flow(system, refining_flow(taken));
  return refine(flow, orbit, taken, state, largest);
}

}  // namespace sympathy
