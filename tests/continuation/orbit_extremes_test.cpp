// A state's largest and smallest value over an orbit (the max_NAME and min_NAME columns, AUTO's
// MAX U(i)), against the closed form on the Lotka-Volterra orbits, whose spikes a parabola
// through the samples resolves poorly.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy {
namespace {

// x' = x (1 - y), y' = y (x - 1): every orbit is a level set of H = x - ln x + y - ln y. x is
// extreme where y = 1, so x - ln x = H - 1 there (the root above 1 its maximum, below 1 its
// minimum), and y likewise where x = 1.
class LotkaVolterra final : public AutoDiffSystem<LotkaVolterra> {
 public:
  LotkaVolterra() { set_parameter_layout({{"a", {0}}}, {1.0}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    dz[0] = z[0] * (1.0 - z[1]);
    dz[1] = z[1] * (z[0] - 1.0);
  }
};

// The root of u - ln u = c on the side of 1 that `above` asks for, by Newton (to rounding).
double level_root(double c, bool above) {
  double u = above ? c + std::log(c) + 1.0 : std::exp(-c);
  for (int k = 0; k < 60; ++k) u -= (u - std::log(u) - c) / (1.0 - 1.0 / u);
  return u;
}

// Started at x = 1, y = 0.05 (where y is at its smallest), the orbit of H = 1.05 - ln 0.05:
// its period T from the return of x through 1 (Newton in time, each iterate integrated at rtol
// 1e-12), 801 samples as the shooting run keeps them, and each extreme refined on the flow
// (orbit_describer.hpp) within 1e-9 relative of the closed form (measured 4e-10 at the minima). The
// parabola through the samples alone is off by more than 1e-7 at x's spike, so the test tells the
// two apart. The minimum of y is the first sample: the samples come back to it, so it is refined
// from the last one before it, across the period's end (the closure error, measured 1.6e-10
// relative).
TEST(OrbitExtremes, LotkaVolterraSpikesToTheClosedForm) {
  const LotkaVolterra system;
  PeriodicOrbit orbit;
  orbit.state0 = Eigen::Vector2d(1.0, 0.05);
  orbit.parameters = system.default_parameters();
  FlowOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  Flow flow(system, o);
  double T = 8.0;  // x crosses 1 again near here (a first look at the orbit)
  for (int k = 0; k < 8; ++k) {
    const Eigen::VectorXd z = flow.advance(orbit.state0, orbit.parameters, 0.0, T);
    T -= (z[0] - 1.0) / (z[0] * (1.0 - z[1]));
  }
  orbit.period = T;
  Eigen::MatrixXd samples(2, PeriodSamples::intervals + 1);
  std::vector<double> times;
  for (int k = 0; k <= PeriodSamples::intervals; ++k)
    times.push_back(T * k / PeriodSamples::intervals);
  int count = 0;
  flow.sample(orbit.state0, orbit.parameters, 0.0, times,
              [&](double, const Eigen::VectorXd& z) { samples.col(count++) = z; });
  ASSERT_EQ(count, samples.cols());
  ASSERT_NEAR(samples(0, count - 1), 1.0, 1e-9) << "the period closes the orbit";

  const double c = 1.05 - std::log(0.05) - 1.0;  // H - 1
  const double x_max = level_root(c, true), x_min = level_root(c, false);
  const double y_max = level_root(c, true), y_min = 0.05;
  const OrbitExtremes refined = refined_extremes(system, orbit, samples);
  EXPECT_NEAR(refined.maxima[0], x_max, 1e-9 * x_max);
  EXPECT_NEAR(refined.minima[0], x_min, 1e-9 * x_min);
  EXPECT_NEAR(refined.maxima[1], y_max, 1e-9 * y_max);
  EXPECT_NEAR(refined.minima[1], y_min, 1e-9 * y_min);
  const Eigen::VectorXd x = samples.row(0).transpose();
  EXPECT_GT(std::abs(sampled_extreme(x, true) - x_max), 1e-7 * x_max)
      << "the parabola alone would pass: the test does not tell the refinement apart";
  // orbit_extreme samples the period itself (a plain flow at rtol 1e-11): the same to 1e-9.
  EXPECT_NEAR(orbit_extreme(system, orbit, 0, true), x_max, 1e-9 * x_max);
}

}  // namespace
}  // namespace sympathy
