// The trust of a detected event: a crossing whose multiplier is not on the unit circle where it
// was located is flagged (multipliers of 1e-17 paired across a step on a long-period orbit are
// not a crossing), a located one on the circle is trusted. And what it rests on: multipliers
// followed across a step within their symmetry, and an event's kind from where it crosses.
#include "sympathy/continuation/detection.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "sympathy/continuation/location.hpp"

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
  const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1.0 + 1e-9));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].type, BifurcationType::BranchPoint);
  EXPECT_TRUE(events[0].trusted()) << events[0].note;
}

TEST(Detection, CrossingOffTheCircleIsNotTrusted) {
  // A "crossing" paired from 1e-17 at a to 3 at b, the multiplier at the located point 1e-17.
  const Step s(1e-17, 3.0);
  const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1e-17));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].trust, EventTrust::CrossingNotResolved);
  EXPECT_NE(events[0].note.find("not on the unit circle"), std::string::npos) << events[0].note;
}

// A complex pair inside the circle (-0.8313 +- 0.0197i, AUTO's pen at I = 0.17976) that meets on
// the negative axis and leaves as two reals, -1.2510 and -0.5524, within one step (at 0.17692):
// one multiplier passed -1, and sign prod(mu + 1) changed. Whichever half of the pair the tracking
// paired with the real outside (issue 33: paired with the lower half, no event at all; with the
// upper, a complex crossing), the step holds one period doubling.
TEST(Detection, PairMeetingOnTheNegativeAxisIsAPeriodDoubling) {
  const std::complex<double> upper(-0.8313, 0.0197), lower = std::conj(upper);
  for (bool lower_goes_out : {true, false}) {
    Step s(0.5, 0.6);  // a real multiplier that stays inside
    Multiplier x1, y1, x2, y2;
    x1.value = lower_goes_out ? lower : upper;
    y1.value = -1.2510;
    x2.value = lower_goes_out ? upper : lower;
    y2.value = -0.5524;
    s.tracked.pairs.push_back({x1, y1});
    s.tracked.pairs.push_back({x2, y2});
    const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(-1.0));
    ASSERT_EQ(events.size(), 1u) << "lower half goes out: " << lower_goes_out;
    EXPECT_EQ(events[0].type, BifurcationType::PeriodDoubling);
    EXPECT_TRUE(events[0].trusted()) << events[0].note;
  }
}

// A fold where the multiplier through +1 reaches the real axis as one of a pair within the step
// (0.98 +- 0.01i at a; 1.03 and 0.95 at b): sign prod(mu - 1) changed, so it is a fold of cycles,
// located and trusted, not a turn "without a multiplier at +1" that stops the branch (issue 33,
// class 2: tor at nu = -0.78759, -0.76041). Without the sign change (the pair still complex at b)
// it remains such a turn.
TEST(Detection, FoldWhoseMultiplierWasComplexIsTrusted) {
  for (bool crosses : {true, false}) {
    Step s(0.5, 0.6);
    s.b.tangent = Eigen::Vector2d(0.0, -1.0);  // the parameter's component changes sign: a turn
    const std::complex<double> upper(0.98, 0.01);
    Multiplier x1, y1, x2, y2;
    x1.value = upper;
    x2.value = std::conj(upper);
    y1.value = crosses ? std::complex<double>(1.03) : std::complex<double>(0.99, 0.005);
    y2.value = crosses ? std::complex<double>(0.95) : std::complex<double>(0.99, -0.005);
    s.tracked.pairs.push_back({x1, y1});
    s.tracked.pairs.push_back({x2, y2});
    const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1.0));
    ASSERT_EQ(events.size(), 1u) << "crosses: " << crosses;
    EXPECT_EQ(events[0].type, BifurcationType::Fold);
    if (crosses) {
      EXPECT_TRUE(events[0].trusted()) << events[0].note;
    } else {
      EXPECT_EQ(events[0].trust, EventTrust::NoCrossingMultiplier);
    }
  }
}

// A locator whose event carries `trivial_error` at the located point and `location` as its
// outcome, the multiplier there `crossing`.
Locator locator_with(std::complex<double> crossing, double trivial_error,
                     LocationOutcome location = LocationOutcome::Located) {
  return
      [=](BifurcationType type, int multiplicity, std::complex<double> a, std::complex<double> b) {
        Bifurcation e = locator_with(crossing)(type, multiplicity, a, b);
        e.floquet.trivial_error = trivial_error;
        e.location = location;
        return e;
      };
}

// A fold is located where the tangent's parameter component vanishes; the multipliers do not
// enter. Its multiplier at +1 meets the trivial one there and is the worst conditioned of all: on
// AUTO's tor (LP at rn = -0.7288775, T 38.94; issue 33) it reads 1.006 at rtol 5e-12 and 0.9999
// at 1e-13 (eigenvalue condition 2e4, found independently), and a bracketing point's trivial
// error was 1.3e-6 where the located point's was 5e-7 (LP at -0.7998992). With a multiplier seen
// crossing +1 in the step, the fold is trusted on its own point's accuracy; a branch point, which
// is located on its multiplier, with the same numbers is not.
TEST(Detection, FoldIsTrustedOnItsTangentNotItsIllConditionedMultiplier) {
  for (bool fold : {true, false}) {
    Step s(0.9, 1.1);
    if (fold) s.b.tangent = Eigen::Vector2d(0.0, -1.0);
    s.a.orbit.floquet.trivial_error = 1.3e-6;
    const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1.006, 5e-7));
    ASSERT_EQ(events.size(), 1u) << "fold: " << fold;
    if (fold) {
      EXPECT_EQ(events[0].type, BifurcationType::Fold);
      EXPECT_TRUE(events[0].trusted()) << events[0].note;
    } else {
      EXPECT_EQ(events[0].type, BifurcationType::BranchPoint);
      EXPECT_EQ(events[0].trust, EventTrust::CrossingNotResolved) << events[0].note;
      EXPECT_NE(events[0].note.find("trivial-multiplier error 1.3e-06"), std::string::npos)
          << events[0].note;
    }
  }
  // The fold's own point still has to be accurate.
  Step s(0.9, 1.1);
  s.b.tangent = Eigen::Vector2d(0.0, -1.0);
  const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1.0, 4e-6));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].trust, EventTrust::TrivialErrorTooLarge) << events[0].note;
}

// A fold's multipliers only show that the monodromy holds nothing but the integration's noise,
// which grows with |M|: on AUTO's tor the fold at T 49.36 (rn = -0.796909055, found to 1e-10 of
// an independent shooting) has a trivial error of 6.9e-6 with |M| = 3,267 at rtol 1e-11, against
// a limit of 1000 rtol |M| = 3.3e-5. The same error is not trusted where |M| is 1 (the limit is
// then the absolute 1e-6), nor on a branch point, which is located on its multipliers.
TEST(Detection, FoldIsTrustedAgainstTheMonodromysNoiseFloor) {
  for (double growth : {1.0, 3267.0}) {
    for (bool fold : {true, false}) {
      Step s(0.9, 1.1);
      if (fold) s.b.tangent = Eigen::Vector2d(0.0, -1.0);
      const Locator base = locator_with(1.0, 6.9e-6);
      const Locator locate = [&](BifurcationType t, int k, std::complex<double> a,
                                 std::complex<double> b) {
        Bifurcation e = base(t, k, a, b);
        e.monodromy_growth = growth;
        return e;
      };
      const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6, 1e-11}, locate);
      ASSERT_EQ(events.size(), 1u);
      EXPECT_EQ(events[0].trusted(), fold && growth > 1.0)
          << "fold " << fold << ", |M| " << growth << ": " << events[0].note;
    }
  }
  // At least the absolute limit, at most 100 times it.
  EXPECT_DOUBLE_EQ((TrustLimit{1e-6, 1e-11}.without_multipliers(3267.0)), 3.267e-5);
  EXPECT_DOUBLE_EQ((TrustLimit{1e-6, 1e-11}.without_multipliers(10.0)), 1e-6);
  EXPECT_DOUBLE_EQ((TrustLimit{1e-6, 1e-11}.without_multipliers(1e14)), 1e-4);
}

// An event location could not narrow to its tolerance is trusted only where its best point's
// multiplier is on the circle: AUTO's tor (issue 33) had a "trusted" BP whose multiplier there
// was 3e-10, not a crossing at all.
TEST(Detection, EventNotNarrowedOffTheCircleIsNotTrusted) {
  const Step s(0.9, 1.1);
  for (double crossing : {3e-10, 1.0 + 1e-6}) {
    const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6},
                               locator_with(crossing, 1e-10, LocationOutcome::NotNarrowed));
    ASSERT_EQ(events.size(), 1u);
    EXPECT_EQ(events[0].trusted(), crossing > 0.5) << crossing << ": " << events[0].note;
  }
}

// A point at parameter (and arclength) s with the given nontrivial multipliers.
ContinuationPoint point_with(double s, std::vector<Multiplier> multipliers) {
  ContinuationPoint p;
  p.parameter = s;
  p.step = s;
  p.unknowns = Eigen::Vector2d(1.0, s);
  p.tangent = Eigen::Vector3d(0.0, 0.0, 1.0);
  p.orbit.floquet.multipliers = std::move(multipliers);
  return p;
}

Multiplier labelled(std::complex<double> value, SymmetryKind symmetry) {
  Multiplier m;
  m.value = value;
  m.symmetry = symmetry;
  return m;
}

// A multiplier that keeps the subspace's symmetry (0.9228, still) and one that breaks it, rising
// from 0.913 through it to 0.933 (the anti-phase k-branch near its BP): eigenvalues of different
// blocks of the monodromy, which cannot exchange. By distance alone the least-cost pairing swaps
// them (0.0002 against 0.0004, squared); by symmetry each is followed as itself, and no other
// multiplier of its own symmetry is near enough to make the pairing doubtful.
// Steps whose multipliers the pairing matched across wrongly: the number outside the unit circle
// (which only crossings change) must be explained by the crossings reported.
struct Pairs {
  ContinuationPoint a, b;
  TrackedMultipliers tracked;
  explicit Pairs(std::initializer_list<std::pair<std::complex<double>, std::complex<double>>> p) {
    for (auto* q : {&a, &b}) {
      q->tangent = Eigen::Vector2d(0.0, 1.0);
      q->orbit.floquet.trivial_error = 1e-10;
    }
    b.index = 1;
    b.parameter = 1.0;
    for (const auto& [x, y] : p) {
      Multiplier mx, my;
      mx.value = x;
      my.value = y;
      tracked.pairs.push_back({mx, my});
    }
  }
};

std::vector<BifurcationType> types_of(const std::vector<Bifurcation>& events) {
  std::vector<BifurcationType> t;
  for (const auto& e : events) t.push_back(e.type);
  return t;
}

TEST(Detection, PairMatchedWithItsHalvesSwappedIsOneCrossing) {
  // 0.9 +- 0.3i leaves through the circle as 1.0 -+ 0.35i: each half paired with the other's
  // successor looked like a crossing of its own (two NS for one pair).
  const std::complex<double> x(0.9, 0.3), y(1.0, 0.35);
  const Pairs s({{x, std::conj(y)}, {std::conj(x), y}});
  const auto events =
      detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(std::polar(1.0, 0.35)));
  EXPECT_EQ(types_of(events), std::vector{BifurcationType::NeimarkSacker});
}

TEST(Detection, PairHiddenByThePairingIsFoundByTheCount) {
  // A real multiplier enters through +1 (1.5 to 0.3) while the pair 0.5 +- 0.8i leaves (to
  // 0.6 +- 0.9i, modulus 1.08). Paired as 1.5 -> 0.6 + 0.9i, 0.5 + 0.8i -> 0.3 and the lower halves
  // together, only the lower halves cross (a pair is followed by its upper half): the count goes
  // from 1 to 2, the real crossing explains -1, the pair the other +2.
  const std::complex<double> x(0.5, 0.8), y(0.6, 0.9);
  const Pairs s({{1.5, y}, {x, 0.3}, {std::conj(x), std::conj(y)}});
  const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1.0));
  auto types = types_of(events);
  std::sort(types.begin(), types.end());
  EXPECT_EQ(types, (std::vector{BifurcationType::BranchPoint, BifurcationType::NeimarkSacker}));
  for (const auto& e : events) EXPECT_TRUE(e.located()) << e.note;
}

TEST(Detection, CountTheCrossingsDoNotExplainIsReportedUnresolved) {
  // Two reals enter through +1 (both signs unchanged: an even number) while a pair leaves, and
  // the pairing shows one real crossing: the count stays at 2, the crossings found explain -1.
  const std::complex<double> x(0.5, 0.8), y(0.6, 0.9);
  const Pairs s({{1.5, y}, {x, 0.3}, {std::conj(x), std::conj(y)}, {1.6, 0.4}});
  const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(1.0));
  const auto unresolved = std::find_if(events.begin(), events.end(), [](const auto& e) {
    return e.trust == EventTrust::CrossingNotResolved;
  });
  ASSERT_NE(unresolved, events.end());
  EXPECT_FALSE(unresolved->located());  // so that the driver tries the step shorter
  EXPECT_NE(unresolved->note.find("from 2 to 2"), std::string::npos) << unresolved->note;
  EXPECT_DOUBLE_EQ(unresolved->parameter, 0.5);  // between the two points, with that uncertainty
  EXPECT_DOUBLE_EQ(unresolved->uncertainty, 0.5);
}

TEST(MultiplierTracking, MultipliersOfDifferentSymmetryPassWithoutExchanging) {
  for (bool with_labels : {true, false}) {
    const SymmetryKind keeps = with_labels ? SymmetryKind::Keeping : SymmetryKind::Unlabelled;
    const SymmetryKind breaks = with_labels ? SymmetryKind::Breaking : SymmetryKind::Unlabelled;
    const ContinuationPoint a = point_with(1.0, {labelled(0.9228, keeps), labelled(0.913, breaks)});
    const ContinuationPoint b = point_with(2.0, {labelled(0.9228, keeps), labelled(0.933, breaks)});
    const TrackedMultipliers t = track(nullptr, a, b);
    ASSERT_EQ(t.pairs.size(), 2u);
    int kept_as_itself = 0;
    for (const auto& [x, y] : t.pairs) kept_as_itself += x.value == y.value ? 1 : 0;
    if (with_labels) {
      EXPECT_EQ(kept_as_itself, 1);
      for (const auto& [x, y] : t.pairs) EXPECT_EQ(x.symmetry, y.symmetry);
      EXPECT_LT(t.ambiguity, 0.5);
    } else {
      EXPECT_EQ(kept_as_itself, 0);  // swapped: what the labels prevent
    }
  }
}

// A real multiplier leaves through +1 and, later in the same step, joins another real one in a
// complex pair: the step's ends see 1.01 (real) and 0.967 + 0.014i, which detection takes for a
// pair crossing. Located, the multiplier that crosses is real (it moves as 1.01 - 0.04 s / s_b,
// the crossing at s = 0.25 s_b): a branch point, at the crossing to the tolerance, with a note.
TEST(Location, ACrossingIsOfTheKindItsMultiplierIsWhereItCrosses) {
  const double sb = 1.0;
  auto real_at = [](double s) { return 1.01 - 0.04 * s; };
  const ContinuationPoint a = point_with(0.0, {labelled(real_at(0.0), SymmetryKind::Breaking)});
  const ContinuationPoint b = point_with(sb, {labelled({0.967, 0.014}, SymmetryKind::Breaking),
                                              labelled({0.967, -0.014}, SymmetryKind::Breaking)});
  int probes = 0;
  const PointAt probe = [&](double s, std::string&) -> std::optional<ContinuationPoint> {
    ++probes;
    return point_with(s, {labelled(real_at(s), SymmetryKind::Breaking)});
  };
  const Bifurcation e = locate(a, b, BifurcationType::NeimarkSacker, 1, real_at(0.0),
                               std::complex<double>(0.967, 0.014), 1e-10, 0.01, probe);
  ASSERT_TRUE(e.located());
  EXPECT_EQ(e.type, BifurcationType::BranchPoint);
  EXPECT_NEAR(e.parameter, 0.25, 1e-10);
  EXPECT_NEAR(e.crossing.real(), 1.0, 1e-10);
  EXPECT_EQ(e.crossing.imag(), 0.0);
  EXPECT_NE(e.note.find("real where it crosses"), std::string::npos) << e.note;
  EXPECT_GT(probes, 0);
}

}  // namespace
}  // namespace sympathy
