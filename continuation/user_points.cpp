// User points (AUTO's UZ): where a step of the branch passes a value of the parameter the user
// asked for, the branch's orbit at that value, corrected with the parameter fixed there (as the
// last point is put on a bound), reported as an event of type UserPoint.
#include <algorithm>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy {

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
      e.location = LocationOutcome::Located;
      e.period = at->orbit.period;
      e.floquet = at->orbit.floquet;
      e.monodromy_growth = at->orbit.monodromy_growth;
      e.state0 = at->orbit.state0;
      e.unknowns = at->unknowns;
      e.tangent = at->tangent;
      e.arclength = at->step;
      e.note = "user point";
      // Located at its parameter value by the corrector, not by the multipliers.
      const double limit = trust_limit().without_multipliers(e.monodromy_growth);
      if (e.floquet.trivial_error > limit) {
        e.trust = EventTrust::TrivialErrorTooLarge;
        e.note = "user point; not trusted: trivial-multiplier error " +
                 format_double(e.floquet.trivial_error) + " above the trust limit " +
                 format_double(limit);
      }
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

}  // namespace sympathy
