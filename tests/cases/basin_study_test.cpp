// The basin study: its tasks (grid point x start, each start drawn from its task index alone),
// its options' checks, and a real small run on the row setup where one state alone is stable.
#include "sympathy/cases/basin_study.hpp"

#include <gtest/gtest.h>

#include "sympathy/core/errors.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

BasinOptions two_grids() {
  BasinOptions o;
  o.grid = {{"k", 40.0, 60.0, 3}, {"c", 0.1, 0.2, 2}};
  o.starts = 4;
  return o;
}

TEST(BasinStudy, TasksAreGridPointTimesStartTheSecondParameterFastest) {
  const ModelSpec spec = testing::load_spec("row2");
  const BasinStudy study(spec, Eigen::VectorXd::Zero(6), two_grids());
  EXPECT_EQ(study.points(), 6u);
  EXPECT_EQ(study.tasks(), 24u);
  const BasinTask t = study.task(13);  // point 3 (k = 50, c = 0.2), start 1
  EXPECT_EQ(t.point, 3u);
  EXPECT_EQ(t.start, 1u);
  EXPECT_EQ(t.values, (std::vector<double>{50.0, 0.2}));
  for (double a : t.angles) {
    EXPECT_GE(a, -0.6);
    EXPECT_LT(a, 0.6);
  }
  // The same angles whenever asked, different ones for another task or seed.
  EXPECT_EQ(study.task(13).angles, t.angles);
  EXPECT_NE(study.task(12).angles, t.angles);
  BasinOptions reseeded = two_grids();
  reseeded.seed = 2;
  EXPECT_NE(BasinStudy(spec, Eigen::VectorXd::Zero(6), reseeded).task(13).angles, t.angles);
}

TEST(BasinStudy, OptionsNameTheField) {
  BasinOptions o = two_grids();
  o.angle_max = -0.7;
  EXPECT_EQ(o.validate()->field, "angle_max");
  o = two_grids();
  o.grid[0].count = 0;
  EXPECT_EQ(o.validate()->field, "grid[0].count");
  o = two_grids();
  o.t_end = 5.0;  // shorter than the classifier's 10 s window
  EXPECT_EQ(o.validate()->field, "t_end");
  o = two_grids();
  o.grid[1].parameter = "q";
  EXPECT_THROW(BasinStudy(testing::load_spec("row2"), Eigen::VectorXd::Zero(6), o), InputError);
  o.grid[1] = {"M", -0.1, 0.3, 3};  // a negative platform mass
  EXPECT_THROW(BasinStudy(testing::load_spec("row2"), Eigen::VectorXd::Zero(6), o), InputError);
}

// Row setup at Table II: only the in-phase orbit is stable (README, "Worked example": the
// anti-phase orbit is unstable below k = 47.07 N/m; Table II's k is 14.7), and the paper's
// simulations end in phase within about 20-25 s (its Figs. 3, 5): every random start must end in
// phase, at the metronomes' 1.733 Hz (README, "Simulation": 1.73296 Hz; within 1e-3 Hz). Some
// starts take longer here: of 8 starts (seed 1) two settled only after 61 and 62 s (task 2 of
// these three among them, not yet settled at 60 s), hence 100 s runs.
TEST(BasinStudy, RowSetupAtTableTwoEndsInPhaseFromEveryStart) {
  BasinOptions o;
  o.grid = {{"k", 14.7467, 14.7467, 1}};
  o.starts = 3;
  o.t_end = 100.0;
  const BasinStudy study(testing::load_spec("row2"), Eigen::VectorXd::Zero(6), o);
  for (std::size_t i = 0; i < study.tasks(); ++i) {
    const auto r = study.run(study.task(i));
    ASSERT_TRUE(r);
    EXPECT_EQ(r->sync.state, SyncState::InPhase) << "task " << i << ": " << r->sync.name;
    EXPECT_NEAR(r->sync.frequency, 1.73296, 1e-3);
    EXPECT_LT(r->sync.time_to_sync, 90.0);
    EXPECT_FALSE(r->orbit);  // not asked to confirm
  }
}

// Confirmation by Newton from a run's end: at Table III the anti-phase orbit is stable
// (README, "Worked example": stable above k = 56.11 and on 47.07-49.69, Table III's k being
// 47.09), and a start of opposite angles (seed 1, task 0: -0.07 and -0.21 rad, which ends
// anti-phase, README "Basins") converges to it: the period of the anti-phase orbit, 0.5814490514 s
// (README, Fig. 8's events: it does not depend on k), within 1e-6 s (the orbit's Newton residual
// is below 1e-9 at the default OrbitOptions, the shooting flow at rtol 1e-11), and stable.
TEST(BasinStudy, ConfirmsALockedEndByNewton) {
  BasinOptions o;
  o.grid = {{"k", 47.0899, 47.0899, 1}};
  o.starts = 1;
  o.t_end = 60.0;
  o.confirm = true;
  const BasinStudy study(testing::load_spec("row2", "table3"), Eigen::VectorXd::Zero(6), o);
  const auto r = study.run(study.task(0));
  ASSERT_TRUE(r);
  ASSERT_EQ(r->sync.state, SyncState::AntiPhase);
  ASSERT_TRUE(r->orbit);
  EXPECT_TRUE(r->orbit->converged);
  EXPECT_NEAR(r->orbit->period, 0.5814490514, 1e-6);
  EXPECT_EQ(r->orbit->stability, Stability::Stable);
  EXPECT_LT(r->orbit->max_modulus, 1.0);
}

TEST(BasinShares, EveryPointListsEveryStateWithItsWilsonInterval) {
  const auto shares = basin_shares(
      2,
      {{0, "anti-phase"}, {0, "in-phase"}, {0, "in-phase"}, {1, "locked+1.00"}, {1, "in-phase"}});
  ASSERT_EQ(shares[0].size(), 3u);
  EXPECT_EQ(shares[0][0].state, "in-phase");  // SyncState's order, then "locked..."
  EXPECT_EQ(shares[0][1].state, "anti-phase");
  EXPECT_EQ(shares[0][2].state, "locked+1.00");
  EXPECT_EQ(shares[0][0].proportion.count, 2u);
  EXPECT_EQ(shares[0][0].proportion.trials, 3u);
  EXPECT_EQ(shares[1][1].proportion.count, 0u);
  EXPECT_EQ(shares[1][1].proportion.lower, 0.0);
}

}  // namespace
}  // namespace sympathy
