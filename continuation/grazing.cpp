// A hybrid orbit's crossings per period, and their change along a branch located (grazing.hpp).
#include "sympathy/continuation/grazing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

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

// Bisection, not a secant on a test function: the count is an integer, and the tangency it
// changes at has no smooth measure common to every surface. The bracket narrows to the location
// tolerance relative to the parameter (or to a hundredth of the window, where the parameter is
// smaller) in about 30 probes. The note compares a with b, not with the last probe beyond: an
// orbit that nearly grazes may cross its surface many times where it turns on it (322 times in
// one run of the metronome's at 1e-10 from its grazing).
CrossingChange Continuation::crossing_change(const ContinuationPoint& a, const ContinuationPoint& b,
                                             const std::vector<int>& at_a,
                                             const std::vector<int>& at_b,
                                             const Eigen::SparseMatrix<double>* jacobian_b) const {
  CrossingChange change;
  double s_near = 0.0, s_far = b.step;
  double p_near = a.parameter, p_far = b.parameter;
  const double tolerance =
      options_.location_tolerance * std::max({std::abs(a.parameter), std::abs(b.parameter),
                                              0.01 * std::abs(options_.upper - options_.lower)});
  constexpr int kMostProbes = 60;
  for (int probe = 0; probe < kMostProbes && std::abs(p_far - p_near) > tolerance; ++probe) {
    const double s = 0.5 * (s_near + s_far);
    std::string why;
    const auto q = point_at(a, s, why, &b, jacobian_b);
    std::vector<int> at_q;
    if (q) {
      try {
        at_q = crossings_of(*q);
      } catch (const IntegrationError& e) {
        why = e.what();
      }
    }
    if (at_q.empty()) {
      change.located = false;
      change.note = "a probe failed: " + why;
      break;
    }
    if (at_q == at_a) {
      s_near = s;
      p_near = q->parameter;
    } else {
      s_far = s;
      p_far = q->parameter;
    }
  }
  change.parameter = 0.5 * (p_near + p_far);
  change.uncertainty = 0.5 * std::abs(p_far - p_near);
  change.arclength = s_far;
  const std::string what = describe_crossing_change(system_, at_a, at_b);
  change.note = change.note.empty() ? what : what + "; " + change.note;
  return change;
}

}  // namespace sympathy
