// User points (ContinuationOptions::user_points, AUTO's UZ): where a branch passes a value asked
// for, its orbit there, at the value exactly, on two families known in closed form.
#include <gtest/gtest.h>

#include "cases/bench/hand_written_systems.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::kTwoPi;
using testing::nontrivial_multiplier;

// The Hopf normal form (cases/examples/hopf.toml by hand): for mu > 0 the circle r = sqrt(mu),
// period 2 pi / w, nontrivial multiplier exp(-4 pi mu / w).
using HopfNormalForm = bench::HandHopf;

BranchProblem problem(const OdeSystem& system, double from, double to, Eigen::Vector2d start,
                      std::optional<double> at = std::nullopt) {
  BranchProblem p;
  p.parameter = 0;
  p.values = system.default_parameters();
  p.from = from;
  p.to = to;
  p.at = at;
  p.start_state = start;
  return p;
}

std::vector<Bifurcation> user_points(const Branch& branch) {
  std::vector<Bifurcation> found;
  for (const auto& e : branch.events)
    if (e.type == BifurcationType::UserPoint) found.push_back(e);
  return found;
}

// mu from 0.25 to 1 with user points 0.3, 0.5 and 1 (the bound: the last point, put on it): each
// at its value to 1e-12 (the correction holds the parameter there, to rounding), its orbit the
// exact circle to the integration's accuracy (rtol 1e-11: radius and period to 1e-8 relative,
// the multiplier to 1e-7 as in equation_system_test), located, trusted, in order along the
// branch, each after the point before it; the branch's points are not changed by them.
TEST(UserPoints, HopfCirclesAtTheValuesAskedFor) {
  const HopfNormalForm system;
  ContinuationOptions options;
  options.user_points = {1.0, 0.5, 0.3};  // any order
  const Branch branch = continue_branch(system, problem(system, 0.25, 1.0, {0.5, 0.0}), options);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  EXPECT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
  const auto uz = user_points(branch);
  ASSERT_EQ(uz.size(), 3u);
  const std::vector<double> expected{0.3, 0.5, 1.0};
  for (std::size_t i = 0; i < uz.size(); ++i) {
    const Bifurcation& e = uz[i];
    const double mu = expected[i];
    EXPECT_NEAR(e.parameter, mu, 1e-12);
    EXPECT_TRUE(e.located()) << e.note;
    EXPECT_TRUE(e.trusted()) << e.note;
    EXPECT_EQ(e.uncertainty, 0.0);
    EXPECT_NEAR(e.state0.norm(), std::sqrt(mu), std::sqrt(mu) * 1e-8);
    EXPECT_NEAR(e.period, kTwoPi, kTwoPi * 1e-8);
    EXPECT_NEAR(nontrivial_multiplier(e.floquet), std::exp(-2 * kTwoPi * mu), 1e-7);
    ASSERT_GE(e.after_point, 0);
    ASSERT_LT(e.after_point + 1, static_cast<int>(branch.points.size()));
    EXPECT_LE(branch.points[e.after_point].parameter, mu);
    EXPECT_GE(branch.points[e.after_point + 1].parameter, mu);
  }
  for (const auto& p : branch.points) EXPECT_TRUE(p.index >= 0 && p.orbit.converged());
}

// The fold normal form's cycles r^2 = (1 +- sqrt(1 + 4 mu)) / 2, a fold at mu = -1/4
// (tests/support/test_systems.hpp): from mu = -0.1 on the outer cycles down through the fold and
// up the inner ones to the bound -0.1. The user point -0.2 is passed twice, on the outer cycle
// (r^2 = 0.7236) and then the inner one (r^2 = 0.2764); -0.1, the start's value, is not reported
// at the start but at the end, on the inner cycle (r^2 = 0.1127). Period 2 pi (theta' = 1).
TEST(UserPoints, PassedTwiceAcrossAFold) {
  const testing::NormalForm system(testing::NormalForm::Kind::Fold, -0.1);
  ContinuationOptions options;
  options.user_points = {-0.2, -0.1};
  const Branch branch = continue_branch(system, problem(system, -0.1, -0.3, {1.0, 0.0}), options);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  const auto uz = user_points(branch);
  ASSERT_EQ(uz.size(), 3u) << branch.stop_reason;
  const double outer = (1 + std::sqrt(0.2)) / 2, inner = (1 - std::sqrt(0.2)) / 2;
  const double last = (1 - std::sqrt(0.6)) / 2;
  const std::vector<std::pair<double, double>> expected{{-0.2, outer}, {-0.2, inner}, {-0.1, last}};
  for (std::size_t i = 0; i < uz.size(); ++i) {
    EXPECT_NEAR(uz[i].parameter, expected[i].first, 1e-12);
    EXPECT_NEAR(uz[i].state0.squaredNorm(), expected[i].second, 1e-8);
    EXPECT_NEAR(uz[i].period, kTwoPi, kTwoPi * 1e-8);
    EXPECT_TRUE(uz[i].located()) << uz[i].note;
  }
  // Along the branch: the fold between the two passes of -0.2.
  ASSERT_EQ(branch.events.size(), 4u);
  EXPECT_EQ(branch.events[1].type, BifurcationType::Fold);
}

// Both ways from mu = 0.5 (the start: not reported) to 0.2 and 0.8: one user point on each part,
// ordered along the joined branch (the backward part's first, its point index negative).
TEST(UserPoints, TwoWayRunReportsEachPartsPoints) {
  const HopfNormalForm system;
  ContinuationOptions options;
  options.user_points = {0.7, 0.5, 0.3};
  const Branch branch =
      continue_branch(system, problem(system, 0.2, 0.8, {0.7, 0.0}, 0.5), options);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  const auto uz = user_points(branch);
  ASSERT_EQ(uz.size(), 2u);
  EXPECT_NEAR(uz[0].parameter, 0.3, 1e-12);
  EXPECT_LT(uz[0].after_point, 0);
  EXPECT_NEAR(uz[0].state0.norm(), std::sqrt(0.3), 1e-8);
  EXPECT_NEAR(uz[1].parameter, 0.7, 1e-12);
  EXPECT_GE(uz[1].after_point, 0);
  EXPECT_NEAR(uz[1].state0.norm(), std::sqrt(0.7), 1e-8);
}

TEST(UserPoints, OptionsRefuseNonFiniteAndRepeatedValues) {
  ContinuationOptions o;
  o.user_points = {0.5, NAN};
  ASSERT_TRUE(o.validate());
  EXPECT_EQ(o.validate()->field, "user_points");
  o.user_points = {0.5, 0.7, 0.5};
  ASSERT_TRUE(o.validate());
  EXPECT_EQ(o.validate()->field, "user_points");
  EXPECT_NE(o.validate()->expected.find("0.5 is given twice"), std::string::npos);
  o.user_points = {0.5, 0.7};
  EXPECT_FALSE(o.validate());
}

}  // namespace
}  // namespace sympathy
