#include "sympathy/core/text.hpp"

#include <cmath>

#include <gtest/gtest.h>

namespace sympathy {
namespace {

// A word of text is a number only where all of it is one; finite_number refuses inf and nan.
TEST(Text, AWordIsANumberOnlyWhereAllOfItIsOne) {
  EXPECT_EQ(whole_number("1.5e-3"), 1.5e-3);
  EXPECT_EQ(whole_number("-2"), -2.0);
  EXPECT_FALSE(whole_number(""));
  EXPECT_FALSE(whole_number("1.5x"));
  EXPECT_FALSE(whole_number("x"));
  EXPECT_FALSE(whole_number("1e999"));  // out of range: std::stod throws
  EXPECT_TRUE(std::isinf(*whole_number("inf")));
  EXPECT_TRUE(std::isnan(*whole_number("nan")));
  EXPECT_EQ(finite_number("0.25"), 0.25);
  EXPECT_FALSE(finite_number("inf"));
  EXPECT_FALSE(finite_number("nan"));
  EXPECT_FALSE(finite_number("2 3"));
}

}  // namespace
}  // namespace sympathy
