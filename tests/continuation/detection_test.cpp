// The trust of a detected event: a crossing whose multiplier is not on the unit circle where it
// was located is flagged (multipliers of 1e-17 paired across a step on a long-period orbit are
// not a crossing), a located one on the circle is trusted.
#include "sympathy/continuation/detection.hpp"

#include <gtest/gtest.h>

namespace sympathy {
namespace {

// Two points a and b between which one real multiplier goes from `from` to `to` (no fold).
struct Step {
  ContinuationPoint a, b;
  TrackedMultipliers tracked;
  Step(double from, double to) {
    for (auto* p : {&a, &b}) {
      p->tangent = Eigen::Vector2d(0.0, 1.0);
      p->orbit.floquet.trivial_error = 1e-10;
    }
    b.index = 1;
    Multiplier x, y;
    x.value = from;
    y.value = to;
    tracked.pairs.push_back({x, y});
  }
};

// A locator that places the event and reports `crossing` as the multiplier there.
Locator locator_with(std::complex<double> crossing) {
  return [crossing](BifurcationType type, int multiplicity, std::complex<double>,
                    std::complex<double>) {
    Bifurcation e;
    e.type = type;
    e.multiplicity = multiplicity;
    e.location = LocationOutcome::Located;
    e.crossing = crossing;
    return e;
  };
}

TEST(Detection, CrossingOnTheCircleIsTrusted) {
  const Step s(0.9, 1.1);
  const auto events = detect(s.tracked, s.a, s.b, 1e-6, locator_with(1.0 + 1e-9));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, BifurcationType::BranchPoint);
  EXPECT_TRUE(events[0].trusted()) << events[0].note;
}

TEST(Detection, CrossingOffTheCircleIsNotTrusted) {
  // A "crossing" paired from 1e-17 at a to 3 at b, the multiplier at the located point 1e-17.
  const Step s(1e-17, 3.0);
  const auto events = detect(s.tracked, s.a, s.b, 1e-6, locator_with(1e-17));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].trust, EventTrust::CrossingNotResolved);
  EXPECT_NE(events[0].note.find("not on the unit circle"), std::string::npos) << events[0].note;
}

}  // namespace
}  // namespace sympathy
