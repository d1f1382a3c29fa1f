// A hybrid orbit's crossings per period, and their change along a branch located (grazing.hpp).
#include "sympathy/continuation/grazing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/core/hybrid_system.hpp"

namespace sympathy {

std::vector<int> crossings_per_period(const OdeSystem& system, const FlowOptions& flow,
                                      const PeriodicOrbit& orbit) {
  if (system.switching_count() == 0 || !dynamic_cast<const HybridSystem*>(&system)) return {};
  // Two crossings inside one step (an orbit just past a grazing) count too: the flow looks for
  // them (Flow::hidden_excursion).
  Flow f(system, flow);
  f.advance(orbit.state0, orbit.parameters, 0.0, orbit.period);
  return f.crossings();
}

std::string describe_crossing_change(const OdeSystem& system, const std::vector<int>& before,
                                     const std::vector<int>& after) {
  std::string out;
  for (std::size_t i = 0; i < std::max(before.size(), after.size()); ++i) {
    const int from = i < before.size() ? before[i] : 0;
    const int to = i < after.size() ? after[i] : 0;
    if (from == to) continue;
    if (!out.empty()) out += ", ";
    out += system.switching_name(static_cast<int>(i)) + " crossed " + std::to_string(from) +
           " -> " + std::to_string(to) + " times a period";
  }
  return out;
}

std::vector<int> Continuation::crossings_of(const ContinuationPoint& p) const {
  return crossings_per_period(system_, options_.orbit.shooting.flow, p.orbit);
}

CrossingBracket bisect_crossing_change(
    double length, const std::vector<int>& before,
    const std::function<std::optional<std::vector<int>>(double, std::string&)>& probe,
    const std::function<bool(double, double)>& narrow) {
  CrossingBracket b;
  b.far = length;
  constexpr int kMostProbes = 60;
  for (int k = 0; k < kMostProbes && !narrow(b.near, b.far); ++k) {
    const double s = 0.5 * (b.near + b.far);
    std::string why;
    const auto at = probe(s, why);
    if (!at) {
      b.failed = why;
      break;
    }
    (*at == before ? b.near : b.far) = s;
  }
  return b;
}

// The bracket narrows to the location tolerance relative to the parameter (or to a hundredth of
// the window, where the parameter is smaller) in about 30 probes. The note compares a with b, not
// with the last probe beyond: an orbit that nearly grazes may cross its surface many times where
// it turns on it (322 times in one run of the metronome's at 1e-10 from its grazing).
CrossingChange Continuation::crossing_change(const ContinuationPoint& a, const ContinuationPoint& b,
                                             const std::vector<int>& at_a,
                                             const std::vector<int>& at_b,
                                             const Eigen::SparseMatrix<double>* jacobian_b) const {
  const double tolerance =
      options_.location_tolerance * std::max({std::abs(a.parameter), std::abs(b.parameter),
                                              0.01 * std::abs(options_.upper - options_.lower)});
  std::map<double, double> parameter_at{{0.0, a.parameter}, {b.step, b.parameter}};
  const CrossingBracket bracket = bisect_crossing_change(
      b.step, at_a,
      [&](double s, std::string& why) -> std::optional<std::vector<int>> {
        const auto q = point_at(a, s, why, &b, jacobian_b);
        if (!q) return std::nullopt;
        try {
          parameter_at[s] = q->parameter;
          return crossings_of(*q);
        } catch (const IntegrationError& e) {
          why = e.what();
          return std::nullopt;
        }
      },
      [&](double near, double far) {
        return std::abs(parameter_at.at(far) - parameter_at.at(near)) <= tolerance;
      });
  const double p_near = parameter_at.at(bracket.near), p_far = parameter_at.at(bracket.far);
  CrossingChange change;
  change.parameter = 0.5 * (p_near + p_far);
  change.uncertainty = 0.5 * std::abs(p_far - p_near);
  change.arclength = bracket.far;
  change.located = bracket.failed.empty();
  change.note = describe_crossing_change(system_, at_a, at_b);
  if (!change.located) change.note += "; a probe failed: " + bracket.failed;
  return change;
}

}  // namespace sympathy
