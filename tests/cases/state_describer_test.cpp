#include "sympathy/cases/state_describer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/core/autodiff_system.hpp"
#include "tests/support/math.hpp"

namespace sympathy {
namespace {

using testing::kPi;

// The Hopf normal form about (c, 0): its cycle is the circle of radius sqrt(mu) about (c, 0),
// period 2 pi / w.
class ShiftedHopf final : public AutoDiffSystem<ShiftedHopf> {
 public:
  ShiftedHopf() { set_parameter_layout({{"mu", {0}}, {"w", {1}}, {"c", {2}}}, {0.25, 1.0, 0.7}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T u = z[0] - p[2], r2 = u * u + z[1] * z[1];
    dz[0] = p[0] * u - p[1] * z[1] - u * r2;
    dz[1] = p[1] * u + p[0] * z[1] - z[1] * r2;
  }
};

// A rotation: the angle th' = 1 + sin(th) / 2 gains 2 pi a period, T = 2 pi / sqrt(1 - 1/4).
class Rotation final : public AutoDiffSystem<Rotation> {
 public:
  Rotation() { set_parameter_layout({{"a", {0}}}, {0.5}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"th"}; }
  std::vector<int> angle_states() const override { return {0}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    using std::sin;
    dz[0] = 1.0 + p[0] * sin(z[0]);
  }
};

// Maxima and minima per state against the closed form (issue 36 item 3, AUTO's MAX U / MIN U):
// the circle of radius r = 0.5 about (0.7, 0), sampled from the angle 1 rad (no sample at an
// extreme): max x = 1.2, min x = 0.2, max y = 0.5 = -min y, to 1e-8 (the describer's own
// integration at rtol 1e-9; the extreme samples alone were r (1 - cos(h / 2)) = 3.9e-6 off at
// worst, h = 2 pi / 800); the amplitudes are r and the rms sqrt(c^2 + r^2 / 2), sqrt(r^2 / 2). A
// rotating angle from th = 0: its minimum 0 at the start, its maximum 2 pi at the end, the end
// samples themselves (to 2e-7, the plain rtol 1e-9 integration's error after a period: measured
// 8e-8).
TEST(StateDescriber, MaximaAndMinimaOfTheClosedFormOrbits) {
  const ShiftedHopf hopf;
  PeriodicOrbit circle;
  circle.parameters = hopf.default_parameters();
  circle.state0 = Eigen::Vector2d(0.7 + 0.5 * std::cos(1.0), 0.5 * std::sin(1.0));
  circle.period = 2 * kPi;
  const StateDescriber describer(hopf);
  const auto s = describer.sizes(circle);
  EXPECT_NEAR(s.maxima[0], 1.2, 1e-8);
  EXPECT_NEAR(s.minima[0], 0.2, 1e-8);
  EXPECT_NEAR(s.maxima[1], 0.5, 1e-8);
  EXPECT_NEAR(s.minima[1], -0.5, 1e-8);
  EXPECT_NEAR(s.amplitudes[0], 0.5, 1e-5);  // half the samples' range, unrefined
  EXPECT_NEAR(s.rms[0], std::sqrt(0.49 + 0.125), 1e-8);
  EXPECT_NEAR(s.rms[1], std::sqrt(0.125), 1e-8);
  // The layout names them, and describe() lists them in its order.
  const auto layout = describer.layout();
  ASSERT_EQ(layout.size(), 4u);
  EXPECT_EQ(layout[2].name, "max");
  EXPECT_EQ(layout[2].csv_prefix, "max_");
  EXPECT_EQ(layout[3].name, "min");
  const auto all = describer.describe(circle);
  ASSERT_EQ(all.size(), 8u);
  EXPECT_EQ(all[4], s.maxima[0]);
  EXPECT_EQ(all[7], s.minima[1]);

  const Rotation rotation;
  PeriodicOrbit turning;
  turning.parameters = rotation.default_parameters();
  turning.state0 = Eigen::VectorXd::Zero(1);
  turning.period = 2 * kPi / std::sqrt(0.75);
  const auto r = StateDescriber(rotation).sizes(turning);
  EXPECT_NEAR(r.minima[0], 0.0, 1e-8);
  EXPECT_NEAR(r.maxima[0], 2 * kPi, 2e-7);
}

}  // namespace
}  // namespace sympathy
