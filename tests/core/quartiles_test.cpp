// Quartiles against NumPy's default (numpy.quantile(x, [0.25, 0.5, 0.75])): [1, 2, 3, 4] gives
// 1.75, 2.5, 3.25; [3, 1, 2] gives 1.5, 2, 2.5; one value is all three; NaNs are left out.
#include "sympathy/core/quartiles.hpp"

#include <gtest/gtest.h>

namespace sympathy {
namespace {

TEST(Quartiles, AsNumPysDefault) {
  const Quartiles a = quartiles({1, 2, 3, 4});
  EXPECT_DOUBLE_EQ(a.q1, 1.75);
  EXPECT_DOUBLE_EQ(a.median, 2.5);
  EXPECT_DOUBLE_EQ(a.q3, 3.25);
  const Quartiles b = quartiles({3, std::nan(""), 1, 2});
  EXPECT_DOUBLE_EQ(b.q1, 1.5);
  EXPECT_DOUBLE_EQ(b.median, 2.0);
  EXPECT_DOUBLE_EQ(b.q3, 2.5);
  const Quartiles c = quartiles({7});
  EXPECT_DOUBLE_EQ(c.q1, 7);
  EXPECT_DOUBLE_EQ(c.q3, 7);
  EXPECT_TRUE(std::isnan(quartiles({}).median));
}

}  // namespace
}  // namespace sympathy
