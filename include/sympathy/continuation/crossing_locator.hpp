// The one locator: where a test function changes sign between two points of a branch, for every
// problem (periodic orbits, equilibria, two-parameter curves) and every event (folds, branch
// points, multipliers or eigenvalues through the circle or the axis, user points).
//
// A bracketing secant (Illinois) in the arclength s from a along a's tangent, each probe a point
// corrected onto the branch there (the problem's `probe`), until the bracket is narrower than the
// tolerance relative to the parameter (and, for a fold, where the parameter is flat, until the
// bracket in s is 1e-7 of the step as well). Two refinements measured on the paper's branches:
//   - with three samples, their inverse quadratic interpolant where it falls inside the bracket:
//     test functions are curved across a step (|mu| - 1 of a multiplier speeding up towards the
//     circle), and on the anti-phase k-branch the secant crept up on the BP and the second NS
//     from one side (5 and 6 probes; 3 and 4 this way);
//   - each probe at least half the tolerance (in arclength) inside each end: a root next to one
//     end is bracketed at once instead of crept up on.
// A test function may follow something from probe to probe (a multiplier by continuity): it
// returns a `Sample` with a tag, and is given the tags of the bracket's current ends.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <utility>

namespace sympathy::driver {

template <class Tag>
struct Sample {
  double value = 0.0;
  Tag tag{};
};

// One end of the bracket: its arclength from a and the test's sample there.
template <class Tag>
struct End {
  double s = 0.0;
  Sample<Tag> sample;
};

struct LocatorOptions {
  double tolerance = 1e-8;  // relative, in the parameter
  double floor = 0.0;       // the parameter's scale is at least this (a hundredth of the window)
  bool fold = false;        // the parameter is flat at the root: the arclength must narrow too
  int max_probes = 30;
  // A probe that cannot be corrected is tried 1e-3 of the bracket to each side (the bordered
  // system of a branch point of equilibria is singular at the point itself).
  bool probe_beside = false;
};

enum class LocatorOutcome {
  Located,      // the bracket is within the tolerance
  ProbeFailed,  // a probe could not be corrected
  NotNarrowed,  // out of probes, or the test's value is not finite at a probe
};

template <class Point, class Tag>
struct Crossing {
  Point point;  // the sample with the least |test| (an end of the step if no probe did better)
  double s = 0.0;
  Sample<Tag> sample;
  double bracket = 0.0;  // the final bracket's width in the parameter
  int probes = 0;
  LocatorOutcome outcome = LocatorOutcome::NotNarrowed;
  std::string why;  // the failed probe's reason
  bool located() const { return outcome == LocatorOutcome::Located; }
};

// `a` and `b` (at arclength `step` from a) with their samples of opposite signs; `test(point, s,
// lo, hi)` -> Sample<Tag>; `probe(s, why)` -> std::optional<Point>; `parameter(point)` -> double.
template <class Point, class Tag, class Test, class Probe, class Parameter>
Crossing<Point, Tag> locate_crossing(const Point& a, const Sample<Tag>& at_a, const Point& b,
                                     const Sample<Tag>& at_b, double step, const Test& test,
                                     const Probe& probe, const Parameter& parameter,
                                     const LocatorOptions& o) {
  Crossing<Point, Tag> c;
  End<Tag> lo{0.0, at_a}, hi{step, at_b};
  double p_lo = parameter(a), p_hi = parameter(b);
  // f: Illinois-scaled values at the ends; g: true values at the ends and at the end last
  // replaced, for the inverse quadratic.
  double f_lo = at_a.value, f_hi = at_b.value;
  const bool a_best = std::abs(f_lo) < std::abs(f_hi);
  c.point = a_best ? a : b;
  c.s = a_best ? 0.0 : step;
  c.sample = a_best ? at_a : at_b;
  double f_best = std::abs(c.sample.value);
  double s_old = 0.0, g_old = 0.0;
  bool third = false;
  int side = 0;  // which end was replaced last (+1 hi, -1 lo): Illinois halves the other's f
  c.outcome = LocatorOutcome::NotNarrowed;
  for (int k = 0; k < o.max_probes; ++k) {
    const double scale = std::max(std::abs(parameter(c.point)), o.floor);
    const bool narrow = std::abs(p_hi - p_lo) <= o.tolerance * scale;
    const bool tight = (hi.s - lo.s) <= 1e-7 * step;
    if ((narrow && (!o.fold || tight)) || f_best == 0.0) {
      c.outcome = LocatorOutcome::Located;
      break;
    }
    const double g_lo = lo.sample.value, g_hi = hi.sample.value;
    double s = hi.s - f_hi * (hi.s - lo.s) / (f_hi - f_lo);
    if (third && g_lo != g_hi && g_lo != g_old && g_hi != g_old) {
      const double q = lo.s * g_hi * g_old / ((g_lo - g_hi) * (g_lo - g_old)) +
                       hi.s * g_lo * g_old / ((g_hi - g_lo) * (g_hi - g_old)) +
                       s_old * g_lo * g_hi / ((g_old - g_lo) * (g_old - g_hi));
      if (q > lo.s && q < hi.s) s = q;
    }
    if (!(s > lo.s && s < hi.s)) s = 0.5 * (lo.s + hi.s);
    const double dp_ds = std::abs(p_hi - p_lo) / (hi.s - lo.s);
    const double half_tolerance =
        o.fold || !(dp_ds > 0.0) ? 0.5e-7 * step : 0.5 * o.tolerance * scale / dp_ds;
    const double inset = std::min(half_tolerance, 0.25 * (hi.s - lo.s));
    s = std::clamp(s, lo.s + inset, hi.s - inset);
    std::string why;
    std::optional<Point> p = probe(s, why);
    ++c.probes;
    if (!p && o.probe_beside)
      for (const double nudge : {1e-3, -1e-3}) {
        const double moved = s + nudge * (hi.s - lo.s);
        if ((p = probe(moved, why))) {
          s = moved;
          break;
        }
      }
    if (!p) {
      c.outcome = LocatorOutcome::ProbeFailed;
      c.why = why;
      break;
    }
    const Sample<Tag> at = test(*p, s, lo, hi);
    if (!std::isfinite(at.value)) break;
    const double f = at.value;
    third = true;
    const double p_at = parameter(*p);
    if (std::abs(f) < f_best) {
      f_best = std::abs(f);
      c.point = std::move(*p);
      c.s = s;
      c.sample = at;
    }
    if (f == 0.0) {
      // The root itself (a normal form's test linear in the arclength: the first secant lands
      // on it): the bracket is the probe, not the side it would have replaced (the Bautin
      // form's Hopf point at b1 = 0 was reported +-0.02, a whole step).
      lo = hi = {s, at};
      p_lo = p_hi = p_at;
      continue;
    }
    if ((f > 0) == (f_hi > 0)) {
      s_old = hi.s;
      g_old = hi.sample.value;
      hi = {s, at};
      p_hi = p_at;
      f_hi = f;
      if (side == +1) f_lo *= 0.5;
      side = +1;
    } else {
      s_old = lo.s;
      g_old = lo.sample.value;
      lo = {s, at};
      p_lo = p_at;
      f_lo = f;
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
  c.bracket = std::abs(p_hi - p_lo);
  return c;
}

}  // namespace sympathy::driver
