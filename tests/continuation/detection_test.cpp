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
                    std::complex<double>, bool) {
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
  // A crossing from 0.5 at a to 3 at b whose located point has its multiplier at 0.5.
  const Step s(0.5, 3.0);
  const auto events = detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, locator_with(0.5));
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].trust, EventTrust::CrossingNotResolved);
  EXPECT_NE(events[0].note.find("not on the unit circle"), std::string::npos) << events[0].note;
}

// A multiplier within its point's noise floor of zero (the trivial multiplier's error, at least
// the absolute trust limit) is not followed across: on AUTO's tor near its homoclinic orbit the
// pairing matched 1,171 at T 49.29 with 1e-22 at T 49.61 and 4e-22 with 18,816, two "crossings"
// (a BP? out and one in), where the number outside the circle stayed 1 and nothing crossed; 40
// such junk events between T 49 and 88 before this rule. Paired alone from 1e-17 to 3, the change
// of the count is reported unresolved, not located (the driver tries the step shorter).
TEST(Detection, MultiplierBelowTheNoiseFloorIsNotFollowedAcross) {
  Step s(1171.0, 1e-22);
  Multiplier x, y;
  x.value = 4e-22;
  y.value = 18816.0;
  s.tracked.pairs.push_back({x, y});
  int located = 0;
  const Locator count = [&](BifurcationType t, int k, std::complex<double> a,
                            std::complex<double> b, bool beside) {
    ++located;
    return locator_with(1.0)(t, k, a, b, beside);
  };
  EXPECT_TRUE(detect(s.tracked, s.a, s.b, TrustLimit{1e-6}, count).empty());
  EXPECT_EQ(located, 0);

  const Step alone(1e-17, 3.0);
  const auto events = detect(alone.tracked, alone.a, alone.b, TrustLimit{1e-6}, count);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(located, 0);
  EXPECT_EQ(events[0].location, LocationOutcome::NotNarrowed);
  EXPECT_EQ(events[0].trust, EventTrust::CrossingNotResolved);
  EXPECT_NE(events[0].note.find("unresolved"), std::string::npos) << events[0].note;
}

// A fold and a branch point in one step, crossed by the same multiplier: it passes +1 at both and
// is on the same side at the two ends (AUTO's tor: 1,171 at T 49.29 and 18,816 at T 49.61, the
// fold at T 49.357 with the multipliers 1.0000093 and 0.9999912 there, trivial error 9.3e-6 with
// |M| = 3,267 at rtol 5e-12). The fold shows itself at its located point by a second multiplier
// at +1 (within the square root of the noise floor's limit, 1.6e-5 here); the branch point beside
// it is located with `beside_fold`. Not where the multiplier at the located turn is far from +1
// (AUTO's fhn canard: 23), nor at the family's Hopf end.
TEST(Detection, FoldWithABranchPointBesideItIsLocatedWithIt) {
  const TrustLimit limit{1e-6, 5e-12};
  for (const char* variant : {"beside", "far from +1", "Hopf end"}) {
    const std::string v = variant;
    Step s(1171.0, 18816.0);
    s.b.tangent = Eigen::Vector2d(0.0, -1.0);
    bool asked_beside = false;
    const Locator locate = [&](BifurcationType t, int k, std::complex<double> a,
                               std::complex<double> b, bool beside) {
      Bifurcation e = locator_with(1.0 + 1e-9)(t, k, a, b, beside);
      e.floquet.trivial_error = 1e-9;
      if (t == BifurcationType::Fold) {
        e.crossing = v == "far from +1" ? 23.0 : 0.9999912;
        e.floquet.trivial_error = 9.3e-6;
        e.monodromy_growth = 3267.0;
      } else {
        asked_beside = beside;
        EXPECT_EQ(a, 1171.0);
        EXPECT_EQ(b, 18816.0);
      }
      return e;
    };
    const TurnEnds hopf_end = [&](const Bifurcation&) { return v == "Hopf end"; };
    const auto events = detect(s.tracked, s.a, s.b, limit, locate, hopf_end);
    if (v == "beside") {
      ASSERT_EQ(events.size(), 2u);
      EXPECT_EQ(events[0].type, BifurcationType::Fold);
      EXPECT_TRUE(events[0].trusted()) << events[0].note;
      EXPECT_EQ(events[1].type, BifurcationType::BranchPoint);
      EXPECT_TRUE(events[1].trusted()) << events[1].note;
      EXPECT_TRUE(asked_beside);
    } else {
      ASSERT_EQ(events.size(), 1u) << v;
      EXPECT_EQ(events[0].trust, EventTrust::NoCrossingMultiplier) << v;
    }
  }
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
  return [=](BifurcationType type, int multiplicity, std::complex<double> a, std::complex<double> b,
             bool beside_fold) {
    Bifurcation e = locator_with(crossing)(type, multiplicity, a, b, beside_fold);
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
                                 std::complex<double> b, bool beside_fold) {
        Bifurcation e = base(t, k, a, b, beside_fold);
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

// The branch point beside a fold, on an exact branch: along arclength s in [0, 1] the parameter is
// p = 0.5 - (s - 0.6)^2 (a fold at s = 0.6) and the multiplier mu = 1 + 10 (s - 0.6)(s - 0.3),
// through +1 at the branch point s = 0.3 and at the fold: 2.8 at a, 3.8 at b, no sign change of
// |mu| - 1 between them. Times the sign of the tangent's parameter component (relative to a's) it
// changes sign at s = 0.3 alone: the branch point at p = 0.41, to the tolerance.
TEST(Location, BranchPointBesideAFoldIsLocatedOnTheProductWithTheTangentsSign) {
  const auto at = [](double s) {
    ContinuationPoint p =
        point_with(s, {labelled(1.0 + 10.0 * (s - 0.6) * (s - 0.3), SymmetryKind::Unlabelled)});
    p.parameter = 0.5 - (s - 0.6) * (s - 0.6);
    p.tangent = Eigen::Vector3d(0.0, 0.0, -2.0 * (s - 0.6));
    return p;
  };
  const PointAt probe = [&](double s, std::string&) -> std::optional<ContinuationPoint> {
    return at(s);
  };
  const ContinuationPoint a = at(0.0), b = at(1.0);
  const Bifurcation e =
      locate(a, b, BifurcationType::BranchPoint, 1, 2.8, 3.8, 1e-10, 0.01, probe, true);
  ASSERT_TRUE(e.located()) << e.note;
  EXPECT_EQ(e.type, BifurcationType::BranchPoint);
  EXPECT_NEAR(e.parameter, 0.41, 1e-9);
  EXPECT_NEAR(e.crossing.real(), 1.0, 1e-8);
}

}  // namespace
}  // namespace sympathy
