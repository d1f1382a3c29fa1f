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
                                const Locator& locate) {
  // The parameter's component of the tangents (the last entry).
  const bool fold = a.tangent[a.tangent.size() - 1] * b.tangent[b.tangent.size() - 1] < 0.0;
  struct Crossing {
    std::complex<double> a, b;
  };
  std::vector<Crossing> plus, minus, complex;
  {
    // Every multiplier that can cross is followed (not the trivial one, nor a family's).
    for (const auto& [mx, my] : tracked.pairs) {
      const auto x = mx.value, y = my.value;
      if ((std::abs(x) - 1.0) * (std::abs(y) - 1.0) >= 0.0) continue;
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
  const auto nearest = [&](double one, bool at_b) {
    std::complex<double> best = 0.0;
    for (const auto& [mx, my] : tracked.pairs) {
      const auto mu = (at_b ? my : mx).value;
      if (std::abs(mu - one) < std::abs(best - one)) best = mu;
    }
    return best;
  };
  // The crossing through `one` made of the multipliers nearest it at the two ends, in place of
  // the complex crossing that was it.
  const auto real_crossing = [&](double one) {
    const auto mu_a = nearest(one, false), mu_b = nearest(one, true);
    std::erase_if(complex, [&](const Crossing& c) {
      return std::abs(c.a - mu_a) <= 1e-12 || std::abs(c.b - mu_b) <= 1e-12 ||
             std::abs(c.a - std::conj(mu_a)) <= 1e-12 || std::abs(c.b - std::conj(mu_b)) <= 1e-12;
    });
    return Crossing{mu_a, mu_b};
  };
  if (minus.empty() && sign_at(-1.0, false) != sign_at(-1.0, true))
    minus.push_back(real_crossing(-1.0));
  if (plus.empty() && sign_at(1.0, false) != sign_at(1.0, true)) plus.push_back(real_crossing(1.0));
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
    Bifurcation e = locate(BifurcationType::Fold, 1, {}, {});
    if (plus_groups.empty()) {
      // A fold of cycles passes a real multiplier through +1; without one the tangent turned
      // where the branch degenerates (an orbit shrinking into an equilibrium turns it back in
      // the scaled norm): not a fold to trust, and the continuation stops there.
      e.note = "no multiplier crossing +1 seen between the bracketing points";
      e.trust = EventTrust::NoCrossingMultiplier;
    }
    report(e, !plus_groups.empty());
    if (!plus_groups.empty()) plus_groups.erase(plus_groups.begin());
  }
  for (const auto& g : plus_groups) {
    Bifurcation e =
        locate(BifurcationType::BranchPoint, static_cast<int>(g.size()), g.front().a, g.front().b);
    if (g.size() > 1) e.note = together_note(e.type, static_cast<int>(g.size()));
    report(e);
  }
  for (const auto& g : clusters(minus)) {
    Bifurcation e = locate(BifurcationType::PeriodDoubling, static_cast<int>(g.size()), g.front().a,
                           g.front().b);
    if (g.size() > 1) e.note = together_note(e.type, static_cast<int>(g.size()));
    report(e);
  }
  for (const auto& g : clusters(complex)) {
    Bifurcation e = locate(BifurcationType::NeimarkSacker, static_cast<int>(g.size()), g.front().a,
                           g.front().b);
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
