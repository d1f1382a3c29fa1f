// The equilibria's part of a stability map (equilibrium_map.hpp): every LP and HB of a branch
// followed once, and the other curve through each BT, ZH, HH point, on normal forms whose curves
// are known in closed form.
#include "sympathy/continuation/equilibrium_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sympathy/core/autodiff_system.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

// The origin with two pairs: mu = b2 + 1 - b1^2 (omega 1) and nu = b2 - 0.25 (omega sqrt 2):
// Hopf curves b2 = b1^2 - 1 (crossed twice by a branch in b1 at b2 = -0.5, at b1 = +-sqrt(0.5))
// and b2 = 0.25 (the second pair), meeting at the double Hopf points b1 = +-sqrt(1.25),
// b2 = 0.25.
class TwoPairs final : public AutoDiffSystem<TwoPairs> {
 public:
  TwoPairs() { set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {0.0, -0.5}); }
  int dimension() const override { return 4; }
  std::vector<std::string> state_names() const override { return {"x", "y", "u", "v"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const P mu = p[1] + 1.0 - p[0] * p[0], nu = p[1] - 0.25;
    const T r2 = z[0] * z[0] + z[1] * z[1], s2 = z[2] * z[2] + z[3] * z[3];
    const double w = std::sqrt(2.0);
    dz[0] = mu * z[0] - z[1] - z[0] * r2;
    dz[1] = z[0] + mu * z[1] - z[1] * r2;
    dz[2] = nu * z[2] - w * z[3] - z[2] * s2;
    dz[3] = w * z[2] + nu * z[3] - z[3] * s2;
  }
};

EquilibriumBranch map_branch(const OdeSystem& system, double from, double to, double at,
                             Eigen::VectorXd start) {
  EquilibriumProblem p;
  p.parameter = 0;
  p.values = system.default_parameters();
  p.from = from;
  p.to = to;
  p.at = at;
  p.start_state = std::move(start);
  return continue_equilibria(system, p, {});
}

EquilibriumCurveOptions map_window(double a0, double a1, double b0, double b1) {
  EquilibriumCurveOptions o;
  o.first_lower = a0;
  o.first_upper = a1;
  o.second_lower = b0;
  o.second_upper = b1;
  return o;
}

// The BT form's branch at b2 = -1 has its HB at b1 = 0 and its LP at b1 = 1/4: their Hopf line
// and fold parabola (each point to 1e-9), each through the BT point at the origin (1e-8), and no
// third curve: the BT on each starts the other, followed already.
TEST(EquilibriumMap, BogdanovTakensFoldAndHopfCurvesEachOnce) {
  const testing::BogdanovTakens system;
  const auto branch = map_branch(system, -0.1, 0.3, 0.1, Eigen::Vector2d(0.1127, 0.0));
  ASSERT_EQ(branch.events.size(), 2u) << branch.stop_reason;
  const auto curves = equilibrium_event_curves(system, branch, 1, map_window(-1, 1, -1.5, 1));
  ASSERT_EQ(curves.size(), 2u);
  int folds = 0, hopfs = 0;
  for (const auto& curve : curves) {
    ASSERT_TRUE(curve.started()) << curve.stop_reason;
    const bool fold = curve.kind == EquilibriumEventType::Fold;
    folds += fold;
    hopfs += !fold;
    for (const auto& p : curve.points)
      EXPECT_NEAR(p.first, fold ? p.second * p.second / 4 : 0.0, 1e-9) << p.index;
    int bt = 0;
    for (const auto& e : curve.events)
      if (e.type == "BT") {
        ++bt;
        EXPECT_NEAR(e.first, 0.0, 1e-8);
        EXPECT_NEAR(e.second, 0.0, 1e-8);
      }
    EXPECT_EQ(bt, 1) << to_string(curve.kind);
  }
  EXPECT_EQ(folds, 1);
  EXPECT_EQ(hopfs, 1);
}

// A branch in b1 at b2 = -0.5 crosses the first pair's Hopf parabola b2 = b1^2 - 1 twice: one
// curve (every point on it to 1e-9, kappa 1), not two. It meets the second pair's Hopf line
// b2 = 0.25 at the double Hopf points b1 = +-sqrt(1.25) (1e-8); the line is followed from the
// first HH (kappa 2, every point at b2 = 0.25 to 1e-9), its own HH at the second located to
// 1e-8, and not followed again from there. Without kappa telling the two Hopf curves through an HH
// point apart, the line would count as followed already.
TEST(EquilibriumMap, HopfCurveCrossedTwiceAndTheOtherPairAtDoubleHopf) {
  const TwoPairs system;
  const auto branch = map_branch(system, -1.0, 1.0, 0.0, Eigen::Vector4d::Zero());
  int hopf_points = 0;
  for (const auto& e : branch.events) hopf_points += e.type == EquilibriumEventType::Hopf;
  ASSERT_EQ(hopf_points, 2) << branch.stop_reason;
  const auto curves = equilibrium_event_curves(system, branch, 1, map_window(-1.5, 1.5, -1.2, 1));
  ASSERT_EQ(curves.size(), 2u);
  const EquilibriumCurve &parabola = curves[0], &line = curves[1];
  ASSERT_TRUE(parabola.started()) << parabola.stop_reason;
  ASSERT_TRUE(line.started()) << line.stop_reason;
  for (const auto& p : parabola.points) {
    EXPECT_NEAR(p.second, p.first * p.first - 1, 1e-9) << p.index;
    EXPECT_NEAR(p.kappa, 1.0, 1e-9) << p.index;
  }
  int hh = 0;
  for (const auto& e : parabola.events)
    if (e.type == "HH") {
      ++hh;
      EXPECT_NEAR(std::abs(e.first), std::sqrt(1.25), 1e-8);
      EXPECT_NEAR(e.second, 0.25, 1e-8);
    }
  EXPECT_EQ(hh, 2);
  EXPECT_EQ(line.origin.rfind("HH at", 0), 0u) << line.origin;
  EXPECT_GT(line.points.size(), 5u);
  for (const auto& p : line.points) {
    EXPECT_NEAR(p.second, 0.25, 1e-9) << p.index;
    EXPECT_NEAR(p.kappa, 2.0, 1e-9) << p.index;
  }
  // The line's own HH, where the first pair crosses: located along b1 though b2 is constant on
  // the line (a bracket in b2 alone said "located" 0.076 off).
  int line_hh = 0;
  for (const auto& e : line.events)
    if (e.type == "HH") {
      ++line_hh;
      EXPECT_TRUE(e.located) << e.note;
      EXPECT_NEAR(e.first, -std::sqrt(1.25), 1e-8);
      EXPECT_NEAR(e.second, 0.25, 1e-8);
    }
  EXPECT_EQ(line_hh, 1);
  EXPECT_TRUE(curve_passes_through(line, std::sqrt(1.25), 0.25, 2.0));
  EXPECT_FALSE(curve_passes_through(line, std::sqrt(1.25), 0.25, 1.0));
}

// An event whose curve cannot start (its window does not hold the branch's value of the second
// parameter) is kept, refused, with its reason.
TEST(EquilibriumMap, RefusedCurveKeptWithItsReason) {
  const testing::BogdanovTakens system;
  const auto branch = map_branch(system, -0.1, 0.3, 0.1, Eigen::Vector2d(0.1127, 0.0));
  const auto curves = equilibrium_event_curves(system, branch, 1, map_window(-1, 1, 0.5, 1));
  ASSERT_EQ(curves.size(), 2u);
  for (const auto& curve : curves) {
    EXPECT_FALSE(curve.started());
    EXPECT_FALSE(curve.stop_reason.empty());
  }
}

}  // namespace
}  // namespace sympathy
