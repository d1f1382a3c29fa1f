#include "sympathy/continuation/location.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "sympathy/continuation/multiplier_tracking.hpp"

namespace sympathy {

Bifurcation locate(const ContinuationPoint& a, const ContinuationPoint& b, BifurcationType type,
                   int multiplicity, std::complex<double> mu_a, std::complex<double> mu_b,
                   double tolerance, double scale_floor, const PointAt& point_at) {
  const int N = static_cast<int>(a.unknowns.size());  // the parameter's entry of the tangents
  const double sb = b.step;
  // The multiplier followed across, by continuity: the one nearest the value interpolated
  // between the multipliers followed at the current ends of the bracket (for a fold, the
  // nontrivial one nearest to 1).
  double s_lo = 0.0, s_hi = sb;
  std::complex<double> mu_lo = mu_a, mu_hi = mu_b;
  auto tracked = [&](const ContinuationPoint& p, double s) {
    const std::complex<double> expected =
        type == BifurcationType::Fold ? 1.0 : mu_lo + (s - s_lo) / (s_hi - s_lo) * (mu_hi - mu_lo);
    std::complex<double> found = 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& m : nontrivial(p.orbit.floquet))
      if (std::abs(m.value - expected) < best) {
        best = std::abs(m.value - expected);
        found = m.value;
      }
    return found;
  };
  // The test function: the tangent's parameter component for a fold; |mu| - 1 of the
  // multiplier followed otherwise.
  auto test = [&](const ContinuationPoint& p, std::complex<double> mu) {
    return type == BifurcationType::Fold ? p.tangent[N] : std::abs(mu) - 1.0;
  };
  Bifurcation e;
  e.type = type;
  e.multiplicity = multiplicity;
  double f_lo = test(a, mu_a), f_hi = test(b, mu_b);
  ContinuationPoint lo = a, hi = b, best = std::abs(f_lo) < std::abs(f_hi) ? a : b;
  double f_best = std::min(std::abs(f_lo), std::abs(f_hi));
  std::complex<double> mu_best = std::abs(f_lo) < std::abs(f_hi) ? mu_a : mu_b;
  double s_best = std::abs(f_lo) < std::abs(f_hi) ? 0.0 : sb;
  int side = 0;  // Illinois: which end was kept last time
  // The true test values at the ends (f_lo and f_hi are Illinois-scaled) and at the end last
  // replaced: three points for inverse quadratic interpolation.
  double g_lo = f_lo, g_hi = f_hi, s_old = 0.0, g_old = 0.0;
  bool third = false;
  for (int iteration = 0; iteration < 30; ++iteration) {
    // Relative to the parameter itself: with a floor of 1 the M-branch's points (M about 0.1
    // kg) were located only to 1e-7 relative.
    const double scale = std::max(std::abs(best.parameter), scale_floor);
    const bool narrow = std::abs(hi.parameter - lo.parameter) <= tolerance * scale;
    const bool tight = (s_hi - s_lo) <= 1e-7 * sb;  // folds: the parameter is flat there
    if ((narrow && (type != BifurcationType::Fold || tight)) || f_best == 0.0) {
      e.location = LocationOutcome::Located;
      break;
    }
    double s = s_hi - f_hi * (s_hi - s_lo) / (f_hi - f_lo);
    // With three points, their inverse quadratic interpolant where it falls inside the bracket:
    // the test functions are curved across a step (|mu| - 1 of a multiplier speeding up towards
    // the circle), and on the anti-phase k-branch the secant crept up on the BP and the second NS
    // from one side (5 and 6 probes; 3 and 4 this way).
    if (third && g_lo != g_hi && g_lo != g_old && g_hi != g_old) {
      const double q = s_lo * g_hi * g_old / ((g_lo - g_hi) * (g_lo - g_old)) +
                       s_hi * g_lo * g_old / ((g_hi - g_lo) * (g_hi - g_old)) +
                       s_old * g_lo * g_hi / ((g_old - g_lo) * (g_old - g_hi));
      if (q > s_lo && q < s_hi) s = q;
    }
    if (!(s > s_lo && s < s_hi)) s = 0.5 * (s_lo + s_hi);
    // At least half the tolerance (in arclength) inside each end: when the root lies next to
    // one end, a probe just past it closes the bracket at once, where the secant would creep up
    // on it from one side.
    const double dp_ds = std::abs(hi.parameter - lo.parameter) / (s_hi - s_lo);
    const double half_tolerance = type == BifurcationType::Fold || !(dp_ds > 0.0)
                                      ? 0.5e-7 * sb
                                      : 0.5 * tolerance * scale / dp_ds;
    const double inset = std::min(half_tolerance, 0.25 * (s_hi - s_lo));
    s = std::clamp(s, s_lo + inset, s_hi - inset);
    std::string why;
    std::optional<ContinuationPoint> probe = point_at(s, why);
    if (!probe) {
      e.location = LocationOutcome::CorrectorFailed;
      e.note = "location stopped: " + why;
      break;
    }
    ContinuationPoint p = std::move(*probe);
    const std::complex<double> mu = tracked(p, s);
    const double f = test(p, mu);
    if (std::abs(f) < f_best) {
      f_best = std::abs(f);
      best = p;
      mu_best = mu;
      s_best = s;
    }
    third = true;
    if ((f > 0) == (f_hi > 0)) {
      s_old = s_hi;
      g_old = g_hi;
      s_hi = s;
      g_hi = f;
      f_hi = f;
      mu_hi = mu;
      hi = std::move(p);
      if (side == +1) f_lo *= 0.5;
      side = +1;
    } else {
      s_old = s_lo;
      g_old = g_lo;
      s_lo = s;
      g_lo = f;
      f_lo = f;
      mu_lo = mu;
      lo = std::move(p);
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
  e.parameter = best.parameter;
  e.arclength = s_best;
  e.bracket = std::abs(hi.parameter - lo.parameter);
  e.uncertainty = e.bracket;
  if (type != BifurcationType::Fold) {
    // The crossing speed over the whole step (a to b), which rounding does not blur as it
    // would a final bracket of 1e-8 relative width.
    const double dp = std::abs(b.parameter - a.parameter);
    const double speed = dp > 0.0 ? std::abs(test(b, mu_b) - test(a, mu_a)) / dp : 0.0;
    const double error = best.orbit.floquet.trivial_error;
    if (speed > 0.0) e.uncertainty += error / speed;
  }
  e.period = best.orbit.period;
  e.floquet = best.orbit.floquet;
  e.crossing = type == BifurcationType::Fold ? tracked(best, 0.0) : mu_best;
  if (type != BifurcationType::Fold) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& m : nontrivial(best.orbit.floquet))
      if (std::abs(m.value - e.crossing) < nearest) {
        nearest = std::abs(m.value - e.crossing);
        e.symmetry = m.symmetry;
      }
  }
  if (e.crossing.imag() < 0.0) e.crossing = std::conj(e.crossing);
  // A step may see a real multiplier on one side of the circle and, on the other, one of a
  // complex pair it has joined since (the anti-phase k-branch's breaking multiplier crosses +1 at
  // k = 47.066 and meets another real one at 47.1): what crosses is what the located point has.
  if (e.location == LocationOutcome::Located && type != BifurcationType::Fold) {
    const bool real = is_real(e.crossing);
    const BifurcationType crossed = !real                     ? BifurcationType::NeimarkSacker
                                    : e.crossing.real() > 0.0 ? BifurcationType::BranchPoint
                                                              : BifurcationType::PeriodDoubling;
    if (crossed != type) {
      e.note = std::string("the multiplier followed is ") + (real ? "real" : "complex") +
               " where it crosses, " + (real ? "complex" : "real") +
               " at an end of the step that found it";
      e.type = crossed;
    }
  }
  e.state0 = best.orbit.state0;
  e.unknowns = best.unknowns;
  e.tangent = best.tangent;
  e.samples = std::move(best.orbit.samples);
  if (e.location == LocationOutcome::NotNarrowed) e.note = "location did not reach the tolerance";
  return e;
}

}  // namespace sympathy
