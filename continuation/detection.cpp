#include "sympathy/continuation/detection.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace sympathy {

namespace {

constexpr double kOnTheCircle = 1e-3;

}  // namespace

std::string together_note(BifurcationType type, int multiplicity) {
  if (multiplicity <= 1) return "";
  const std::string count = std::to_string(multiplicity);
  switch (type) {
    case BifurcationType::NeimarkSacker:
      return count + " complex pairs cross together";
    case BifurcationType::PeriodDoubling:
      return count + " multipliers cross -1 together";
    default:
      return count + " multipliers cross +1 together";
  }
}

std::vector<Bifurcation> detect(const TrackedMultipliers& tracked, const ContinuationPoint& a,
                                const ContinuationPoint& b, const TrustLimit& trust,
                                const Locator& locate, const TurnEnds& turn_ends) {
  // The parameter's component of the tangents (the last entry).
  const bool fold = a.tangent[a.tangent.size() - 1] * b.tangent[b.tangent.size() - 1] < 0.0;
  struct Crossing {
    std::complex<double> a, b;
  };
  std::vector<Crossing> plus, minus, complex;
  const double floor_a = std::max(trust.absolute, a.orbit.floquet.trivial_error),
               floor_b = std::max(trust.absolute, b.orbit.floquet.trivial_error);
  {
    // Every multiplier that can cross is followed (not the trivial one, nor a family's). One
    // within its point's noise floor of zero (the multipliers' error, of which the trivial one's
    // is the measure, and never below the absolute trust limit) is indistinguishable from zero:
    // following it "across" pairs noise with a multiplier elsewhere (issue 33: on AUTO's tor near
    // its homoclinic orbit, multipliers of 1e-17 to 1e-45 followed to 1.1 gave 40 junk BP?, PD?
    // and NS? between T 49 and 88). A true crossing from there passes resolved values first; if
    // one step jumps over them, the count of multipliers outside the circle changes unexplained,
    // and the step is refined.
    for (const auto& [mx, my] : tracked.pairs) {
      const auto x = mx.value, y = my.value;
      if ((std::abs(x) - 1.0) * (std::abs(y) - 1.0) >= 0.0) continue;
      if (std::abs(x) <= floor_a || std::abs(y) <= floor_b) continue;
      if (is_real(x) && is_real(y)) {
        (x.real() > 0 ? plus : minus).push_back({x, y});
      } else if (x.imag() > 0.0 || y.imag() > 0.0) {
        complex.push_back({x, y});  // one of each conjugate pair
      }
    }
  }
  // What no collision off the circle can change (a complex pair contributes |mu + 1|^2 > 0):
  // the sign of prod(mu + 1) over the followed multipliers changes exactly when an odd number of
  // real multipliers pass -1. A pair that meets on the negative axis and sends one through -1
  // within one step was bucketed as a complex crossing, or (paired the other way) as none, and the
  // period doubling passed silently (issue 33: AUTO's pen near I = 0.17916, tor near
  // nu = -0.61496). Then the multipliers nearest -1 at the two ends are the crossing, located as
  // a period doubling; the complex crossing that was this one is dropped.
  // The same of prod(mu - 1) and +1: an odd number of real multipliers through +1 (a fold of
  // cycles, or a branch point) changes its sign. A multiplier that reaches the real axis near +1
  // as one of a pair and passes +1 within the step was no "real crossing", and the fold beside it
  // looked like a turn without a multiplier at +1, which stops a branch (issue 33, class 2: tor,
  // fhn).
  const auto sign_at = [&](double one, bool at_b) {
    int sign = 1;
    for (const auto& [mx, my] : tracked.pairs) {
      const auto mu = (at_b ? my : mx).value;
      if (is_real(mu) && (mu.real() - one) * one > 0.0) sign = -sign;  // beyond `one`
    }
    return sign;
  };
  // The multiplier nearest `one` at an end, among those beyond it (or among those not), above
  // the end's noise floor.
  const auto nearest = [&](double one, bool at_b, bool beyond) {
    std::complex<double> best = 0.0;
    double distance = INFINITY;
    for (const auto& [mx, my] : tracked.pairs) {
      const auto mu = (at_b ? my : mx).value;
      if (std::abs(mu) <= (at_b ? floor_b : floor_a)) continue;
      if (beyond != (is_real(mu) && (mu.real() - one) * one > 0.0)) continue;
      if (std::abs(mu - one) < distance) {
        distance = std::abs(mu - one);
        best = mu;
      }
    }
    return best;
  };
  const auto beyond_count = [&](double one, bool at_b) {
    int n = 0;
    for (const auto& [mx, my] : tracked.pairs) {
      const auto mu = (at_b ? my : mx).value;
      n += is_real(mu) && (mu.real() - one) * one > 0.0;
    }
    return n;
  };
  // The crossing through `one`, in place of the complex crossing that was it, or of a pairing
  // with a multiplier below the floor: at the end with more real multipliers beyond `one`, the
  // one of them nearest it; at the other, the multiplier short of it nearest it (on tor at
  // nu = -0.7876 the multiplier 38.3 dropped to 0.028 in one step while the pairing followed it to
  // -2.9e-10: the nearest to +1 at both ends, regardless of side, was 3e-12 and 0.028).
  const auto real_crossing = [&](double one, std::vector<Crossing>& into) {
    const bool fewer_at_b = beyond_count(one, true) < beyond_count(one, false);
    const auto mu_a = nearest(one, false, fewer_at_b), mu_b = nearest(one, true, !fewer_at_b);
    if (mu_a == 0.0 || mu_b == 0.0) return;  // one end has none above its floor: unexplained
    std::erase_if(complex, [&](const Crossing& c) {
      return std::abs(c.a - mu_a) <= 1e-12 || std::abs(c.b - mu_b) <= 1e-12 ||
             std::abs(c.a - std::conj(mu_a)) <= 1e-12 || std::abs(c.b - std::conj(mu_b)) <= 1e-12;
    });
    into.push_back({mu_a, mu_b});
  };
  const bool through_minus = sign_at(-1.0, false) != sign_at(-1.0, true);
  const bool through_plus = sign_at(1.0, false) != sign_at(1.0, true);
  if (minus.empty() && through_minus) real_crossing(-1.0, minus);
  if (plus.empty() && through_plus) real_crossing(1.0, plus);
  // One complex pair is one crossing: paired across the step with its halves swapped (upper at
  // a with lower at b), each half looked like a crossing of its own.
  for (std::size_t i = 0; i < complex.size(); ++i)
    for (std::size_t j = complex.size(); j-- > i + 1;)
      if (std::abs(complex[j].a - std::conj(complex[i].a)) <= 1e-12 &&
          std::abs(complex[j].b - std::conj(complex[i].b)) <= 1e-12)
        complex.erase(complex.begin() + static_cast<std::ptrdiff_t>(j));
  // The number of multipliers outside the unit circle, which only crossings change: each
  // crossing found explains a change of one (real) or two (a pair). What they leave unexplained
  // is a crossing the pairing hid: a change of two with both signs unchanged is a pair through
  // the circle (an NS), made of the complex multipliers nearest the circle at the two ends;
  // anything else is reported unresolved (and the step refined: it is not located).
  const auto outside = [&](bool at_b) {
    int n = 0;
    for (const auto& [mx, my] : tracked.pairs) n += std::abs((at_b ? my : mx).value) > 1.0;
    return n;
  };
  const auto direction = [](const Crossing& c) { return std::abs(c.b) > 1.0 ? 1 : -1; };
  int explained = 0;
  for (const auto& c : plus) explained += direction(c);
  for (const auto& c : minus) explained += direction(c);
  for (const auto& c : complex) explained += 2 * direction(c);
  const int count_a = outside(false), count_b = outside(true);
  int unexplained = count_b - count_a - explained;
  if (std::abs(unexplained) == 2 && complex.empty()) {
    const auto nearest_circle = [&](bool at_b) {
      std::complex<double> best = 0.0;
      double distance = INFINITY;
      for (const auto& [mx, my] : tracked.pairs) {
        const auto mu = (at_b ? my : mx).value;
        if (mu.imag() > 0.0 && !is_real(mu) && std::abs(std::abs(mu) - 1.0) < distance) {
          distance = std::abs(std::abs(mu) - 1.0);
          best = mu;
        }
      }
      return best;
    };
    const Crossing pair{nearest_circle(false), nearest_circle(true)};
    if (pair.a != 0.0 && pair.b != 0.0 && (std::abs(pair.a) - 1.0) * (std::abs(pair.b) - 1.0) < 0 &&
        2 * direction(pair) == unexplained) {
      complex.push_back(pair);
      unexplained = 0;
    }
  }
  // Crossings with equal multipliers happen together (symmetry): one event, its multiplicity.
  auto clusters = [](const std::vector<Crossing>& c) {
    std::vector<std::vector<Crossing>> groups;
    for (const auto& x : c) {
      bool placed = false;
      for (auto& g : groups)
        if (std::abs(g.front().a - x.a) <= 1e-6 * std::max(1.0, std::abs(x.a))) {
          g.push_back(x);
          placed = true;
          break;
        }
      if (!placed) groups.push_back({x});
    }
    return groups;
  };
  std::vector<Bifurcation> found;
  // `on_tangent`: a fold with a multiplier seen crossing +1 in the step. It is located where the
  // tangent's parameter component vanishes, which the multipliers do not enter: the multiplier
  // there only labels it, and at a fold it is the worst conditioned of all (it meets the trivial
  // one: on AUTO's tor, 1.006 at rtol 5e-12, 0.9999 at 1e-13, with an eigenvalue condition of
  // 2e4), so neither the circle nor the bracketing points' accuracy is asked of it; the located
  // point's own trivial error still is.
  auto report = [&](Bifurcation e, bool on_tangent = false) {
    e.after_point = a.index;
    // A crossing has its multiplier on the unit circle at the located point (to the location's
    // tolerance times the multiplier's speed: far below 1e-3 on the branches measured); one that
    // is not there was a pairing of unresolved multipliers across the step, not a crossing. The
    // same of an event that location could not narrow to its tolerance: its best point's
    // multiplier is all there is to show the crossing.
    if (!on_tangent && e.trust == EventTrust::Trusted &&
        std::abs(std::abs(e.crossing) - 1.0) > kOnTheCircle) {
      e.trust = EventTrust::CrossingNotResolved;
      std::ostringstream msg;
      msg << "not trusted: the multiplier followed across is " << std::abs(e.crossing)
          << " in modulus at the located point, not on the unit circle (multipliers not resolved)";
      e.note += (e.note.empty() ? "" : "; ") + msg.str();
    }
    const double worst = on_tangent
                             ? e.floquet.trivial_error
                             : std::max({a.orbit.floquet.trivial_error,
                                         b.orbit.floquet.trivial_error, e.floquet.trivial_error});
    const double trust_limit =
        on_tangent ? trust.without_multipliers(e.monodromy_growth) : trust.absolute;
    if (worst > trust_limit) {
      if (e.trust == EventTrust::Trusted) e.trust = EventTrust::TrivialErrorTooLarge;
      std::ostringstream msg;
      msg << "not trusted: trivial-multiplier error " << worst << " above " << trust_limit;
      e.note += (e.note.empty() ? "" : "; ") + msg.str();
    }
    found.push_back(std::move(e));
  };
  auto plus_groups = clusters(plus);
  if (fold) {
    Bifurcation e = locate(BifurcationType::Fold, 1, {}, {}, false);
    // The real multiplier nearest +1 at an end, on either side of it.
    const auto nearest_one = [&](bool at_b) {
      const auto beyond = nearest(1.0, at_b, true), short_of = nearest(1.0, at_b, false);
      if (short_of == 0.0) return beyond;  // none (0 stands for none)
      if (beyond == 0.0) return short_of;
      return std::abs(beyond - 1.0) < std::abs(short_of - 1.0) ? beyond : short_of;
    };
    const auto mu_a = nearest_one(false), mu_b = nearest_one(true);
    // A fold with a branch point beside it in the same step: the fold's multiplier passed +1 at
    // both, and is on the same side at the two ends (AUTO's tor near its homoclinic orbit: 1,171
    // at T 49.29, 18,816 at T 49.61, the fold at T 49.357 and a branch point 0.004 before it).
    // The fold shows itself at its located point, where its multiplier meets the trivial one at
    // +1 (a Jordan block: the two split by the square root of the perturbation, so within the
    // square root of the noise floor's limit). Not at the family's end, where the orbits shrink
    // into an equilibrium and the critical pair's multipliers meet at +1 too.
    const bool beside =
        plus_groups.empty() && !through_plus && is_real(mu_a) && is_real(mu_b) && mu_a != 0.0 &&
        mu_b != 0.0 && (std::abs(mu_a) - 1.0) * (std::abs(mu_b) - 1.0) > 0.0 &&
        e.location == LocationOutcome::Located &&
        std::abs(e.crossing - 1.0) <= std::sqrt(trust.without_multipliers(e.monodromy_growth)) &&
        !(turn_ends && turn_ends(e));
    if (plus_groups.empty() && !beside) {
      // A fold of cycles passes a real multiplier through +1; without one the tangent turned
      // where the branch degenerates (an orbit shrinking into an equilibrium turns it back in
      // the scaled norm): not a fold to trust, and the continuation stops there.
      e.note = "no multiplier crossing +1 seen between the bracketing points";
      e.trust = EventTrust::NoCrossingMultiplier;
    }
    if (beside) e.note = "its multiplier at +1 at the located point, a branch point beside it";
    report(e, !plus_groups.empty() || beside);
    if (!plus_groups.empty()) plus_groups.erase(plus_groups.begin());
    if (beside) report(locate(BifurcationType::BranchPoint, 1, mu_a, mu_b, true));
  }
  for (const auto& g : plus_groups) {
    Bifurcation e = locate(BifurcationType::BranchPoint, static_cast<int>(g.size()), g.front().a,
                           g.front().b, false);
    if (g.size() > 1) e.note = together_note(e.type, static_cast<int>(g.size()));
    report(e);
  }
  for (const auto& g : clusters(minus)) {
    Bifurcation e = locate(BifurcationType::PeriodDoubling, static_cast<int>(g.size()), g.front().a,
                           g.front().b, false);
    if (g.size() > 1) e.note = together_note(e.type, static_cast<int>(g.size()));
    report(e);
  }
  for (const auto& g : clusters(complex)) {
    Bifurcation e = locate(BifurcationType::NeimarkSacker, static_cast<int>(g.size()), g.front().a,
                           g.front().b, false);
    if (g.size() > 1) e.note = together_note(e.type, static_cast<int>(g.size()));
    report(e);
  }
  if (unexplained != 0) {
    // Not located, so that the step is tried shorter (the driver's location retries); reported
    // between the two points if it stays unexplained.
    Bifurcation e;
    e.type =
        std::abs(unexplained) % 2 ? BifurcationType::BranchPoint : BifurcationType::NeimarkSacker;
    e.after_point = a.index;
    e.parameter = 0.5 * (a.parameter + b.parameter);
    e.uncertainty = 0.5 * std::abs(b.parameter - a.parameter);
    e.bracket = std::abs(b.parameter - a.parameter);
    e.arclength = 0.5 * b.step;
    e.location = LocationOutcome::NotNarrowed;
    e.trust = EventTrust::CrossingNotResolved;
    e.period = 0.5 * (a.orbit.period + b.orbit.period);
    e.floquet = b.orbit.floquet;
    e.state0 = b.orbit.state0;
    e.unknowns = b.unknowns;
    e.tangent = b.tangent;
    std::ostringstream msg;
    msg << "unresolved: the number of multipliers outside the unit circle went from " << count_a
        << " to " << count_b << " between these points, which the crossings found do not explain";
    e.note = msg.str();
    found.push_back(std::move(e));
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
  return found;
}

}  // namespace sympathy
