#include "sympathy/core/proportion.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace sympathy {

Proportion wilson_interval(std::size_t count, std::size_t trials, double z) {
  if (count > trials) throw std::invalid_argument("wilson_interval: count above trials");
  if (!(z > 0.0)) throw std::invalid_argument("wilson_interval: z must be positive");
  Proportion p;
  p.count = count;
  p.trials = trials;
  if (trials == 0) return p;
  const double n = static_cast<double>(trials);
  const double q = static_cast<double>(count) / n;
  const double z2 = z * z;
  // The roots in P of (q - P)^2 = z^2 P (1 - P) / n.
  const double centre = (q + z2 / (2.0 * n)) / (1.0 + z2 / n);
  const double half = z / (1.0 + z2 / n) * std::sqrt(q * (1.0 - q) / n + z2 / (4.0 * n * n));
  p.share = q;
  // Exact at the ends: count 0 gives lower 0, count == trials gives upper 1 (rounding aside).
  p.lower = count == 0 ? 0.0 : std::max(0.0, centre - half);
  p.upper = count == trials ? 1.0 : std::min(1.0, centre + half);
  return p;
}

}  // namespace sympathy
