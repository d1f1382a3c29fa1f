#include "sympathy/continuation/stability_map.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>

#include "curve_crossing.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

double rotation_of(const Bifurcation& e) {
  return e.type == BifurcationType::NeimarkSacker ? std::abs(std::arg(e.crossing)) / (2 * M_PI)
                                                  : std::nan("");
}

}  // namespace

bool curve_passes_through(const BifurcationCurve& curve, double first, double value,
                          double rotation) {
  return detail::passes_through(curve.points, first, value,
                                [&](const CurvePoint& a, const CurvePoint& b, double t) {
                                  if (std::isnan(rotation)) return true;
                                  const double turn = a.rotation + t * (b.rotation - a.rotation);
                                  return std::abs(turn - rotation) <= 2e-3;
                                });
}

std::vector<BifurcationCurve> event_curves(const OdeSystem& system, const Branch& branch,
                                           int second, const CurveOptions& options,
                                           const CurveCallbacks& callbacks) {
  std::vector<BifurcationCurve> curves;
  for (const auto& e : branch.events) {
    if (!e.located() || e.trust == EventTrust::NoCrossingMultiplier ||
        e.trust == EventTrust::CrossingNotResolved)
      continue;
    if (e.type == BifurcationType::UserPoint) continue;  // a value asked for, no bifurcation
    if (e.type == BifurcationType::BranchPoint && e.symmetry != SymmetryKind::Breaking) continue;
    const double value = system.parameter(branch.start_values, second);
    const bool covered = std::any_of(curves.begin(), curves.end(), [&](const BifurcationCurve& c) {
      return c.kind == e.type && curve_passes_through(c, e.parameter, value, rotation_of(e));
    });
    if (covered) continue;
    if (callbacks.stop_requested && callbacks.stop_requested()) break;
    try {
      curves.push_back(continue_curve(system, branch, e, second, options, callbacks));
    } catch (const std::invalid_argument& refused) {
      // An event no curve can follow (an NS pair in a block of one dimension): kept, refused.
      BifurcationCurve none;
      none.kind = e.type;
      none.first = branch.parameter;
      none.second = second;
      none.first_name = branch.parameter_name;
      none.second_name = system.parameter_names().at(second);
      none.origin =
          to_string(e.type) + " at " + branch.parameter_name + " = " + format_number(e.parameter);
      none.stop = StopReason::StartFailed;
      none.stop_reason = refused.what();
      curves.push_back(std::move(none));
    }
  }
  // One generation more: where a curve met another bifurcation ("NS-LP": another multiplier
  // crossed the unit circle there), the other curve through that point, unless already followed.
  const std::size_t first_generation = curves.size();
  std::vector<std::pair<double, double>> tried;
  for (std::size_t c = 0; c < first_generation; ++c) {
    for (const CurveEvent& meeting : std::vector<CurveEvent>(curves[c].events)) {
      // At a 1:1 resonance an NS curve's pair meets at +1 and one multiplier goes on through
      // it: a BP curve (breaking block) or an LP curve starts there; at 1:2, a PD curve.
      const bool resonance = meeting.type == "R1" || meeting.type == "R2";
      const SymmetryKind symmetry = resonance ? curves[c].symmetry : meeting.crossing_symmetry;
      const auto dash = meeting.type.find('-');
      if (!resonance && (dash == std::string::npos || meeting.type.rfind("turn", 0) == 0)) continue;
      const std::string other = !resonance                           ? meeting.type.substr(dash + 1)
                                : meeting.type == "R2"               ? std::string("PD")
                                : symmetry == SymmetryKind::Breaking ? std::string("BP")
                                                                     : std::string("LP");
      // An unlocated meeting is tried too, from where its probes got (the curve's start is
      // corrected onto it at that value of the second parameter): probes of an NS-LP point can
      // fail near it (the in-phase (k, c) map's at k = 56.07). Not, it seems, because the NS
      // test function's exterior square holds the trivial multiplier times the one at +1: where
      // that crossing is no fold of the orbit the NS curve locates it (bifurcation_curve_test,
      // RotationAndGrowth); at an LP the orbit itself folds, its shooting Jacobian singular.
      if (!meeting.located &&
          meeting.uncertainty > 0.01 * (options.first_upper - options.first_lower))
        continue;
      // A point tried already (located again from another probe sequence, or a start that
      // failed) is not tried twice.
      const auto same = [&](const std::pair<double, double>& t) {
        return std::abs(t.first - meeting.first) <= 1e-6 * std::max(1.0, std::abs(t.first)) &&
               std::abs(t.second - meeting.second) <= 1e-6 * std::max(1.0, std::abs(t.second));
      };
      if (std::any_of(tried.begin(), tried.end(), same)) continue;
      tried.emplace_back(meeting.first, meeting.second);
      const BifurcationType kinds[] = {BifurcationType::Fold, BifurcationType::BranchPoint,
                                       BifurcationType::PeriodDoubling,
                                       BifurcationType::NeimarkSacker};
      const auto kind = std::find_if(std::begin(kinds), std::end(kinds),
                                     [&](BifurcationType t) { return to_string(t) == other; });
      if (kind == std::end(kinds)) continue;
      const bool covered =
          std::any_of(curves.begin(), curves.end(), [&](const BifurcationCurve& k) {
            return k.kind == *kind && curve_passes_through(k, meeting.first, meeting.second,
                                                           *kind == BifurcationType::NeimarkSacker
                                                               ? meeting.at.rotation
                                                               : std::nan(""));
          });
      if (covered) continue;
      if (callbacks.stop_requested && callbacks.stop_requested()) return curves;
      // The meeting point as an event of a one-point branch at its second parameter's value.
      Branch at;
      at.parameter = branch.parameter;
      at.parameter_name = branch.parameter_name;
      at.start_values = system.with_parameter(branch.start_values, second, meeting.second);
      at.points.resize(1);
      at.points[0].orbit.subspace = branch.points.front().orbit.subspace;
      Bifurcation e;
      e.type = *kind;
      e.parameter = meeting.first;
      e.period = meeting.at.period;
      e.state0 = meeting.at.state0;
      e.floquet = meeting.at.floquet;
      e.location = LocationOutcome::Located;
      e.symmetry = symmetry;
      try {
        BifurcationCurve born = continue_curve(system, at, e, second, options, callbacks);
        born.origin = meeting.type + " point at " + branch.parameter_name + " = " +
                      format_number(meeting.first) + ", " + curves[c].second_name + " = " +
                      format_number(meeting.second);
        curves.push_back(std::move(born));
      } catch (const std::invalid_argument&) {
        // A meeting the curve code cannot start from (a BP of no declared symmetry): skipped.
      }
    }
  }
  return curves;
}

StabilityGrid stability_grid(const OdeSystem& system, const Branch& branch, int second,
                             double first_lower, double first_upper, double second_lower,
                             double second_upper, int first_points, int second_points,
                             const OrbitOptions& options,
                             const std::function<bool()>& stop_requested) {
  const Stopwatch clock;
  if (first_points < 2 || second_points < 2)
    throw std::invalid_argument("stability grid: expected at least 2 x 2 points");
  if (branch.points.empty()) throw std::invalid_argument("stability grid: the branch is empty");
  StabilityGrid g;
  for (int j = 0; j < first_points; ++j)
    g.first.push_back(first_lower + (first_upper - first_lower) * j / (first_points - 1));
  for (int i = 0; i < second_points; ++i)
    g.second.push_back(second_lower + (second_upper - second_lower) * i / (second_points - 1));
  g.unstable_count.assign(second_points, std::vector<int>(first_points, -1));
  g.max_modulus.assign(second_points, std::vector<double>(first_points, NAN));
  const InvariantSubspace& subspace = branch.points.front().orbit.subspace;
  const double base = system.parameter(branch.start_values, second);
  // The rows in the order they are reached from the branch's value: upwards, then downwards.
  std::vector<int> up, down;
  for (int i = 0; i < second_points; ++i) (g.second[i] >= base ? up : down).push_back(i);
  std::reverse(down.begin(), down.end());
  std::optional<PeriodicOrbit> previous_column;
  for (int j = 0; j < first_points; ++j) {
    if (stop_requested && stop_requested()) break;
    const auto nearest = std::min_element(
        branch.points.begin(), branch.points.end(), [&](const auto& a, const auto& b) {
          return std::abs(a.parameter - g.first[j]) < std::abs(b.parameter - g.first[j]);
        });
    const ParameterValues at_base =
        system.with_parameter(branch.start_values, branch.parameter, g.first[j]);
    PeriodicOrbit start = solve_periodic_orbit(system, at_base, nearest->orbit.state0,
                                               nearest->orbit.period, subspace, options);
    // Beyond the branch's end (it stopped short of the window) the nearest point can be far:
    // the previous column's orbit is then the better guess.
    if (!start.converged() && previous_column)
      start = solve_periodic_orbit(system, at_base, previous_column->state0,
                                   previous_column->period, subspace, options);
    if (start.converged()) previous_column = start;
    for (const auto* rows : {&up, &down}) {
      if (!start.converged()) break;
      PeriodicOrbit previous = start;
      for (int i : *rows) {
        const ParameterValues p = system.with_parameter(at_base, second, g.second[i]);
        PeriodicOrbit o =
            solve_periodic_orbit(system, p, previous.state0, previous.period, subspace, options);
        if (!o.converged()) break;  // the rest of this direction stays unknown
        g.unstable_count[i][j] = o.floquet.unstable_count;
        g.max_modulus[i][j] = o.floquet.max_modulus;
        previous = std::move(o);
      }
    }
  }
  for (const auto& row : g.unstable_count)
    g.failures += static_cast<int>(std::count(row.begin(), row.end(), -1));
  g.seconds = clock.seconds();
  return g;
}

}  // namespace sympathy
