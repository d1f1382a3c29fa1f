#include "sympathy/continuation/equilibrium_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "curve_crossing.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy {

namespace {

bool near(double a, double b) {
  return std::abs(a - b) <= 1e-6 * std::max(1.0, std::abs(b));
}

// Whether a curve of `kind` (with `kappa` there, for a Hopf curve) already passes through
// (first, second): crossing `second` there, or with a located codimension-two point there (a
// curve along which `second` hardly changes, the double Hopf form's line b2 = 0.25 through both
// its HH points, or one that turns in `first` there, the BT form's fold parabola at its BT,
// which its chords miss by 6e-4).
bool covered(const std::vector<EquilibriumCurve>& curves, EquilibriumEventType kind, double first,
             double second, double kappa) {
  return std::any_of(curves.begin(), curves.end(), [&](const EquilibriumCurve& c) {
    if (c.kind != kind) return false;
    if (curve_passes_through(c, first, second, kappa)) return true;
    return std::any_of(c.events.begin(), c.events.end(), [&](const EquilibriumCurveEvent& e) {
      return e.located && near(e.first, first) && near(e.second, second) &&
             (std::isnan(kappa) ||
              std::abs(e.at.kappa - kappa) <= 1e-2 * std::max(1e-12, std::abs(kappa)) ||
              std::abs(e.at.kappa - kappa) <= 1e-6);
    });
  });
}

}  // namespace

bool curve_passes_through(const EquilibriumCurve& curve, double first, double value, double kappa) {
  double scale = 0.0;
  for (const auto& p : curve.points)
    if (std::isfinite(p.kappa)) scale = std::max(scale, std::abs(p.kappa));
  using Point = EquilibriumCurvePoint;
  return detail::passes_through(curve.points, first, value,
                                [&](const Point& a, const Point& b, double t) {
                                  if (std::isnan(kappa)) return true;
                                  const double k = a.kappa + t * (b.kappa - a.kappa);
                                  return std::abs(k - kappa) <= 1e-2 * std::max(scale, 1e-12);
                                });
}

std::vector<EquilibriumCurve> equilibrium_event_curves(const OdeSystem& system,
                                                       const EquilibriumBranch& branch, int second,
                                                       const EquilibriumCurveOptions& options,
                                                       const EquilibriumCurveCallbacks& callbacks) {
  const auto stopped = [&] { return callbacks.stop_requested && callbacks.stop_requested(); };
  std::vector<EquilibriumCurve> curves;
  const double value = system.parameter(branch.start_values, second);
  for (const auto& e : branch.events) {
    if (!e.located) continue;
    if (e.type != EquilibriumEventType::Fold && e.type != EquilibriumEventType::Hopf) continue;
    const double kappa = e.type == EquilibriumEventType::Hopf && e.hopf
                             ? e.hopf->omega * e.hopf->omega
                             : std::nan("");
    if (covered(curves, e.type, e.parameter, value, kappa)) continue;
    if (stopped()) return curves;
    try {
      curves.push_back(continue_equilibrium_curve(system, branch, e, second, options, callbacks));
    } catch (const std::invalid_argument& refused) {
      // An event no curve can follow (its window does not hold it): kept, refused.
      EquilibriumCurve none;
      none.kind = e.type;
      none.first = branch.parameter;
      none.second = second;
      none.first_name = branch.parameter_name;
      none.second_name = system.parameter_names().at(second);
      none.state_names = branch.state_names;
      none.origin =
          to_string(e.type) + " at " + branch.parameter_name + " = " + format_double(e.parameter);
      none.start_values = branch.start_values;
      none.stop = StopReason::StartFailed;
      none.stop_reason = refused.what();
      curves.push_back(std::move(none));
    }
  }
  // One generation more: the other curve through each BT, ZH and HH point of these.
  const std::size_t first_generation = curves.size();
  for (std::size_t c = 0; c < first_generation; ++c) {
    for (const EquilibriumCurveEvent& meeting :
         std::vector<EquilibriumCurveEvent>(curves[c].events)) {
      if (!meeting.located) continue;
      if (meeting.type != "BT" && meeting.type != "ZH" && meeting.type != "HH") continue;
      const CodimensionTwoPoint point = codimension_two_point(system, curves[c], meeting);
      CurveFromCodimensionTwo next;
      try {
        next = curve_from_codimension_two(system, point);
      } catch (const std::invalid_argument&) {
        continue;  // no pair for a Hopf curve there: nothing starts
      }
      if (covered(curves, next.kind, meeting.first, meeting.second, next.kappa)) continue;
      if (stopped()) return curves;
      try {
        curves.push_back(continue_from_codimension_two(system, point, options, callbacks));
      } catch (const std::invalid_argument&) {
        // A point outside the window (located on its edge) starts nothing.
      }
    }
  }
  return curves;
}

}  // namespace sympathy
