// User points (AUTO's UZ): where a step of the branch passes a value of the parameter the user
// asked for, the branch's orbit at that value, corrected with the parameter fixed there (as the
// last point is put on a bound), reported as an event of type UserPoint. User values: the same
// where a quantity of the orbits passes a value (a period, corrected with the period held; a
// state's extreme over the period, on the one locator).
#include <algorithm>
#include <cmath>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/crossing_locator.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

// The event of the corrected orbit `at`: trusted on its corrector alone. Its value (the parameter
// asked for, or where the quantity takes its value) and its orbit are what the corrector solved
// for, to its tolerance; its multipliers do not enter them. Where they are not resolved (a trivial
// error above the noise floor TrustLimit::without_multipliers allows) the note says that its
// stability there is unknown. (They had untrusted it: AUTO's pen at T = 30, whose stops at
// AUTO's parameters were trusted or not as the trivial error, 1e-4 to 6e-3 at |M| 1e10, fell
// either side of the ceiling 1e-4 from one start of the transient to the next.)
void describe_located(Bifurcation& e, const ContinuationPoint& at, const TrustLimit& trust,
                      const std::string& note) {
  e.location = LocationOutcome::Located;
  e.period = at.orbit.period;
  e.floquet = at.orbit.floquet;
  e.monodromy_growth = at.orbit.monodromy_growth;
  e.state0 = at.orbit.state0;
  e.unknowns = at.unknowns;
  e.tangent = at.tangent;
  // The period's samples from the corrector's own run, as a located event keeps them: a plain
  // integration of the period from state0 diverges on strongly unstable orbits (AUTO's pen at
  // T = 30, |M| 1e10: ps1's maximum 1e-3 off).
  e.samples = at.orbit.samples;
  e.note = note;
  const double limit = trust.without_multipliers(e.monodromy_growth);
  if (e.floquet.trivial_error > limit)
    e.note = note + "; its multipliers not resolved (trivial-multiplier error " +
             format_number(e.floquet.trivial_error) + " above " + format_number(limit) +
             "): its stability here unknown";
}

}  // namespace

std::vector<Bifurcation> Continuation::user_points_between(const ContinuationPoint& a,
                                                           const ContinuationPoint& b) const {
  std::vector<Bifurcation> found;
  for (const double value : options_.user_points) {
    // Passed: a and b on either side, or b on it (a on it was reported with the step before;
    // the start is not reported).
    if (!((a.parameter - value) * (b.parameter - value) < 0.0 || b.parameter == value)) continue;
    Bifurcation e;
    e.type = BifurcationType::UserPoint;
    e.parameter = value;  // exact: the correction holds the parameter at it
    e.after_point = a.index;
    const std::optional<ContinuationPoint> at =
        b.parameter == value ? std::optional<ContinuationPoint>(b) : point_on_bound(a, b, value);
    if (at) {
      // Located at its parameter value by the corrector, not by the multipliers.
      describe_located(e, *at, trust_limit(), "user point");
      e.arclength = at->step;
    } else {
      // Kept, with what the points around it say (a step whose own corrector converged, so a
      // rare case; a bifurcation in it gets shorter retries, a user point does not need them).
      const double t = (value - a.parameter) / (b.parameter - a.parameter);
      e.location = LocationOutcome::CorrectorFailed;
      // Nothing interpolated is trusted (issue 33: AUTO's pp2 had such a point trusted, its period
      // 8e-4 off).
      e.trust = EventTrust::NotCorrected;
      e.period = a.orbit.period + t * (b.orbit.period - a.orbit.period);
      e.state0 = a.orbit.state0 + t * (b.orbit.state0 - a.orbit.state0);
      e.unknowns = a.unknowns + t * (b.unknowns - a.unknowns);
      e.tangent = a.tangent;
      e.arclength = t * b.step;
      e.note =
          "not trusted: the orbit at this value could not be corrected; state and period "
          "interpolated between the points around it";
    }
    found.push_back(std::move(e));
  }
  std::sort(found.begin(), found.end(),
            [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
  return found;
}

double Continuation::quantity(const UserValue& v, const ContinuationPoint& p) const {
  if (v.quantity == UserValue::Quantity::Period) return p.orbit.period;
  if (v.quantity == UserValue::Quantity::AtSection) return p.orbit.state0[v.state];
  return orbit_extreme(system_, p.orbit, v.state, v.quantity == UserValue::Quantity::Maximum);
}

std::vector<std::pair<Bifurcation, bool>> Continuation::user_values_between(
    const ContinuationPoint& a, const ContinuationPoint& b,
    const Eigen::SparseMatrix<double>* jacobian_b) const {
  std::vector<std::pair<Bifurcation, bool>> found;
  const int N = problem_->unknowns();
  for (const UserValue& v : options_.user_values) {
    double qa = 0.0, qb = 0.0;
    try {
      qa = quantity(v, a);
      qb = quantity(v, b);
    } catch (const IntegrationError&) {
      continue;  // a period that cannot be integrated has no extreme to compare
    }
    // Passed, or reached at b (at a it was reported with the step before).
    if (!((qa - v.value) * (qb - v.value) < 0.0 || qb == v.value)) continue;
    Bifurcation e;
    e.type = BifurcationType::UserPoint;
    e.after_point = a.index;
    const std::string note =
        (v.stop ? "stop at " : "user value ") + v.name + " = " + format_double(v.value);
    std::optional<ContinuationPoint> at;
    std::string why;
    if (qb == v.value) {
      at = b;
    } else if (v.quantity == UserValue::Quantity::Period) {
      at = point_where(a, b, N - 1, v.value);  // exact: the period held at the value
      if (!at) why = "the orbit with this period could not be corrected";
    } else {
      // An extreme (or a state at the section) is located on the one locator in arclength along
      // a's tangent, to the location tolerance in the parameter and 1e-7 of the step.
      driver::LocatorOptions o;
      o.tolerance = options_.location_tolerance;
      o.floor = 0.01 * (options_.upper - options_.lower);
      o.fold = true;
      using Ends = driver::End<int>;
      const auto test = [&](const ContinuationPoint& p, double, const Ends&, const Ends&) {
        return driver::Sample<int>{quantity(v, p) - v.value, 0};
      };
      const auto probe = [&](double s, std::string& reason) {
        return point_at(a, s, reason, &b, jacobian_b);
      };
      try {
        auto located = driver::locate_crossing(
            a, driver::Sample<int>{qa - v.value, 0}, b, driver::Sample<int>{qb - v.value, 0},
            b.step, test, probe, [](const ContinuationPoint& p) { return p.parameter; }, o);
        if (located.located()) {
          at = std::move(located.point);
          at->step = located.s;
          e.bracket = located.bracket;
        } else {
          why = located.why.empty() ? "the locator did not narrow it" : located.why;
        }
      } catch (const IntegrationError& error) {
        why = error.what();
      }
    }
    if (at) {
      describe_located(e, *at, trust_limit(), note);
      e.parameter = at->parameter;
      e.uncertainty = e.bracket;
      e.arclength = at->step;
    } else {
      // Reported where it was passed, untrusted: nothing interpolated is trusted.
      const double t = (v.value - qa) / (qb - qa);
      e.location = LocationOutcome::CorrectorFailed;
      e.trust = EventTrust::NotCorrected;
      e.parameter = a.parameter + t * (b.parameter - a.parameter);
      e.uncertainty = std::abs(b.parameter - a.parameter);
      e.period = a.orbit.period + t * (b.orbit.period - a.orbit.period);
      e.state0 = a.orbit.state0 + t * (b.orbit.state0 - a.orbit.state0);
      e.unknowns = a.unknowns + t * (b.unknowns - a.unknowns);
      e.tangent = a.tangent;
      e.arclength = t * b.step;
      e.note = note + "; not trusted: " + why + "; interpolated between the points around it";
    }
    found.emplace_back(std::move(e), v.stop);
  }
  std::sort(found.begin(), found.end(),
            [](const auto& x, const auto& y) { return x.first.arclength < y.first.arclength; });
  return found;
}

}  // namespace sympathy
