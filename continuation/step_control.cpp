#include "sympathy/continuation/step_control.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sympathy {

double parameter_limited_step(double ds, double dp_per_ds, const ContinuationOptions& options) {
  if (ds * dp_per_ds > options.max_parameter_step)
    return std::max(options.max_parameter_step / dp_per_ds, options.min_step);
  return ds;
}

MultiplierMotion multiplier_motion(const TrackedMultipliers& tracked, double ds,
                                   const ContinuationOptions& options) {
  MultiplierMotion m;
  // A multiplier near the circle whose modulus moves far in one step may hide a window of
  // instability; one whose match is doubtful makes crossings unreliable.
  m.too_far = tracked.ambiguity > 0.5;
  double watched_change = 0.0;  // largest change of |mu| near the circle in this step
  for (const auto& [mx, my] : tracked.pairs) {
    const auto x = mx.value, y = my.value;
    const bool near =
        std::min(std::abs(std::abs(x) - 1.0), std::abs(std::abs(y) - 1.0)) < options.watch_band;
    if (near) watched_change = std::max(watched_change, std::abs(std::abs(x) - std::abs(y)));
  }
  m.too_far |= watched_change > options.max_modulus_change;
  m.aim = std::numeric_limits<double>::infinity();
  if (watched_change > 0.0) m.aim = 0.75 * options.max_modulus_change / watched_change * ds;
  if (tracked.ambiguity > 0.0) m.aim = std::min(m.aim, std::sqrt(0.3 / tracked.ambiguity) * ds);
  return m;
}

}  // namespace sympathy
