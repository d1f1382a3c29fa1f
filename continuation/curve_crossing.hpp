// Whether a two-parameter curve passes through a point: the question a map asks before it follows
// a curve from an event (the cycles' event_curves, the equilibria's equilibrium_event_curves), so
// that no curve is followed twice. Internal to the continuation layer.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sympathy::detail {

// Whether the chord between two consecutive `points` (each with .first and .second) crosses
// `value` of the second parameter within 1e-4 relative of `first` or, where the points lie far
// apart, within half their distance in the first; and `matches(a, b, t)` there (a quantity that
// tells two curves through one point apart, interpolated at t between a and b).
template <class Point, class Matches>
bool passes_through(const std::vector<Point>& points, double first, double value,
                    const Matches& matches) {
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Point &a = points[i], &b = points[i + 1];
    if ((a.second - value) * (b.second - value) > 0.0) continue;
    const double t = a.second == b.second ? 0.0 : (value - a.second) / (b.second - a.second);
    const double at = a.first + t * (b.first - a.first);
    const double tolerance =
        std::max(1e-4 * std::max(1.0, std::abs(first)), 0.5 * std::abs(b.first - a.first));
    if (std::abs(at - first) > tolerance) continue;
    if (matches(a, b, t)) return true;
  }
  return false;
}

}  // namespace sympathy::detail
