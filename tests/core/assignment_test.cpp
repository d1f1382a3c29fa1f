#include "sympathy/core/assignment.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

namespace sympathy {
namespace {

double total(const Eigen::MatrixXd& cost, const std::vector<int>& column) {
  double sum = 0.0;
  for (int i = 0; i < static_cast<int>(column.size()); ++i) sum += cost(i, column[i]);
  return sum;
}

// Expected: the least total over all n! permutations, by enumeration.
TEST(Assignment, LeastTotalOfAllPermutations) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  for (int n = 1; n <= 7; ++n)
    for (int trial = 0; trial < 20; ++trial) {
      Eigen::MatrixXd cost(n, n);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) cost(i, j) = uniform(random);
      if (trial % 4 == 0) cost = cost.array().round();  // ties
      std::vector<int> p(n);
      std::iota(p.begin(), p.end(), 0);
      double best = std::numeric_limits<double>::infinity();
      do best = std::min(best, total(cost, p));
      while (std::next_permutation(p.begin(), p.end()));
      const auto column = least_cost_assignment(cost);
      std::vector<int> sorted = column;
      std::sort(sorted.begin(), sorted.end());
      for (int j = 0; j < n; ++j) ASSERT_EQ(sorted[j], j) << "not a permutation, n = " << n;
      EXPECT_NEAR(total(cost, column), best, 1e-12) << "n = " << n << ", trial " << trial;
    }
}

// Two points moving side by side by more than half their gap: nearest neighbours cross them over,
// the least total of squared distances does not.
TEST(Assignment, KeepsTwoPointsMovingSideBySideApart) {
  const double before[] = {0.130, 0.177}, after[] = {0.100, 0.147};
  Eigen::MatrixXd cost(2, 2);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) cost(i, j) = std::pow(before[i] - after[j], 2);
  EXPECT_LT(std::abs(before[0] - after[1]), std::abs(before[0] - after[0]));  // greedy crosses
  const auto column = least_cost_assignment(cost);
  EXPECT_EQ(column[0], 0);
  EXPECT_EQ(column[1], 1);
}

TEST(Assignment, RejectsANonSquareMatrix) {
  EXPECT_THROW(least_cost_assignment(Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
