#include "sympathy/core/proportion.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace sympathy {
namespace {

// Newcombe, Stat. Med. 17, 857-872 (1998), Table I, method 3 (the Wilson score interval without
// continuity correction), his four examples, printed to 4 decimals: tolerance 5e-5.
TEST(WilsonInterval, NewcombesExamples) {
  struct Case {
    std::size_t count, trials;
    double lower, upper;
  };
  for (const Case& c : {Case{81, 263, 0.2553, 0.3662}, Case{15, 148, 0.0624, 0.1605},
                        Case{0, 20, 0.0, 0.1611}, Case{1, 29, 0.0061, 0.1718}}) {
    const Proportion p = wilson_interval(c.count, c.trials);
    EXPECT_NEAR(p.lower, c.lower, 5e-5) << c.count << " of " << c.trials;
    EXPECT_NEAR(p.upper, c.upper, 5e-5) << c.count << " of " << c.trials;
    EXPECT_DOUBLE_EQ(p.share, static_cast<double>(c.count) / c.trials);
  }
}

// Every run in one state: the interval reaches 1 exactly and its lower end is
// n / (n + z^2) (the root of the Wilson equation at p = 1): 20 / (20 + 1.96^2) = 0.8389.
TEST(WilsonInterval, AllOrNothingAndEmpty) {
  const Proportion all = wilson_interval(20, 20);
  EXPECT_EQ(all.upper, 1.0);
  EXPECT_NEAR(all.lower, 20.0 / (20.0 + kZ95 * kZ95), 1e-15);
  const Proportion none = wilson_interval(0, 0);
  EXPECT_EQ(none.lower, 0.0);
  EXPECT_EQ(none.upper, 1.0);
  EXPECT_THROW(wilson_interval(3, 2), std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
