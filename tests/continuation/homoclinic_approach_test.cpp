// The end of a family at a homoclinic orbit: the period doubled on a trailing stretch of points
// whose parameters lie within the tolerance of the last one's, and still growing.
#include "sympathy/continuation/homoclinic_approach.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace sympathy {
namespace {

// The first prefix of `history` at which the approach is recognised.
std::optional<HomoclinicApproach> first(const std::vector<PeriodRecord>& history,
                                        double tolerance) {
  std::vector<PeriodRecord> prefix;
  for (const auto& h : history) {
    prefix.push_back(h);
    if (auto found = homoclinic_approach(prefix, tolerance)) return found;
  }
  return std::nullopt;
}

// At a saddle p(T) = p_h + exp(-T / 2): within 1e-4 of the last point from T_k with
// exp(-T_k / 2) = 1e-4 + exp(-T / 2), T_k = 18.42 for any T above 30, so on a grid of 0.5 the
// stretch starts at 18.5 and the period has doubled at T = 37 exactly (at 36.5 it has not).
TEST(HomoclinicApproach, SaddleEndsWhereThePeriodDoubledWithinTheTolerance) {
  std::vector<PeriodRecord> history;
  for (double T = 10.0; T <= 100.0; T += 0.5) history.push_back({0.7 + std::exp(-T / 2), T});
  const auto h = first(history, 1e-4);
  ASSERT_TRUE(h);
  EXPECT_DOUBLE_EQ(h->to_period, 37.0);
  EXPECT_DOUBLE_EQ(h->from_period, 18.5);
  EXPECT_LE(h->parameter_spread, 1e-4);
  EXPECT_NEAR(h->parameter, 0.7, 1e-8);
}

// At a saddle-focus the parameter winds about p_h, p = p_h + exp(-0.3 T) cos(0.63 T), with folds
// every pi / 0.63 of period: its amplitude falls below 1e-4 at T = ln(1e4) / 0.3 = 30.7, so the
// stretch starts near there and the end comes near twice that, not at the folds before.
TEST(HomoclinicApproach, SaddleFocusEndsPastItsFolds) {
  std::vector<PeriodRecord> history;
  for (double T = 8.0; T <= 100.0; T += 0.25)
    history.push_back({-0.7969 + std::exp(-0.3 * T) * std::cos(0.63 * T), T});
  const auto h = first(history, 1e-4);
  ASSERT_TRUE(h);
  EXPECT_GT(h->to_period, 50.0);
  EXPECT_LT(h->to_period, 2 * 30.7 + 0.5);
  EXPECT_GE(h->to_period, 2 * h->from_period);
}

// AUTO's fhn (a, T) along its family from HB1, measured: the canard explosion grows the period
// from 6.5 to 16.9 with a fixed to 1e-6 from 0.43052, by 1.6 times within 1e-4 of it. No end.
TEST(HomoclinicApproach, CanardExplosionIsNoEnd) {
  const std::vector<PeriodRecord> fhn = {
      {0.4228457485, 6.52345}, {0.4234466363, 6.61648}, {0.4243967364, 6.77835},
      {0.4251547227, 6.92367}, {0.4266413775, 7.26893}, {0.4290144795, 8.1932},
      {0.4301908438, 9.48967}, {0.4304508735, 10.6783}, {0.4305006776, 11.6103},
      {0.4305132256, 12.4308}, {0.4305159007, 12.9095}, {0.4305164866, 13.0864},
      {0.4305165796, 13.1196}, {0.4305165904, 13.1236}, {0.4305166155, 13.1329},
      {0.4305166737, 13.155},  {0.4305168556, 13.2297}, {0.4305173314, 13.481},
      {0.4305180349, 14.321},  {0.4305182356, 15.7678}, {0.4305182411, 16.0447},
      {0.430518243, 16.2083},  {0.4305182434, 16.255},  {0.4305182434, 16.8838}};
  EXPECT_FALSE(first(fhn, 1e-4 * 0.4305));
}

// A period that stopped growing is no approach, whatever came before.
TEST(HomoclinicApproach, OnlyWhileThePeriodGrows) {
  std::vector<PeriodRecord> history = {{0.5, 10.0}, {0.5, 15.0}, {0.5, 21.0}};
  EXPECT_TRUE(homoclinic_approach(history, 1e-6));
  history.push_back({0.5, 20.0});
  EXPECT_FALSE(homoclinic_approach(history, 1e-6));
}

// Orbits unresolved (errors above 1e-2) while the period grows by a quarter: from T = 40 on a grid
// of 1, the end comes at T = 50 exactly (at 49, 49 / 40 < 1.25). A resolved point in between starts
// the stretch again; a period that grew 13% and fell (ab's strongly unstable part) is no end.
TEST(HomoclinicApproach, UnresolvedOrbitsWhileThePeriodGrows) {
  std::vector<PeriodRecord> history;
  std::optional<HomoclinicApproach> found;
  for (double T = 30.0; T <= 60.0 && !found; T += 1.0) {
    history.push_back({0.17 + 0.01 * std::exp(-T / 10), T, T >= 40.0 ? 0.3 : 1e-5});
    found = unresolved_approach(history);
  }
  ASSERT_TRUE(found);
  EXPECT_DOUBLE_EQ(found->to_period, 50.0);
  EXPECT_DOUBLE_EQ(found->from_period, 40.0);
  history[history.size() - 5].trivial_error = 1e-5;  // resolved at T = 46: the stretch is 47-50
  EXPECT_FALSE(unresolved_approach(history));
  std::vector<PeriodRecord> ab;
  for (double T : {13.0, 13.5, 14.0, 14.5, 14.7, 14.6, 14.0, 13.0}) {
    ab.push_back({0.1307, T, 20.0});
    EXPECT_FALSE(unresolved_approach(ab)) << T;
  }
}

}  // namespace
}  // namespace sympathy
