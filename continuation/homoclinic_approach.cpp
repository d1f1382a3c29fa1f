#include "sympathy/continuation/homoclinic_approach.hpp"

#include <algorithm>
#include <cmath>

namespace sympathy {

namespace {

// The trailing stretch of points `in_stretch` takes, if the period grew over it by `factor` and
// still grows at the last point.
template <class InStretch>
std::optional<HomoclinicApproach> grown_over_stretch(const std::vector<PeriodRecord>& history,
                                                     double factor, const InStretch& in_stretch) {
  const PeriodRecord& last = history.back();
  if (!(last.period > history[history.size() - 2].period)) return std::nullopt;  // not growing
  HomoclinicApproach h{last.parameter, last.period, last.period, 0.0};
  for (auto it = history.rbegin(); it != history.rend() && in_stretch(*it); ++it) {
    h.from_period = std::min(h.from_period, it->period);
    h.parameter_spread = std::max(h.parameter_spread, std::abs(it->parameter - last.parameter));
  }
  if (last.period >= factor * h.from_period) return h;
  return std::nullopt;
}

}  // namespace

std::optional<HomoclinicApproach> homoclinic_approach(const std::vector<PeriodRecord>& history,
                                                      double tolerance) {
  if (history.size() < 3) return std::nullopt;
  const double p = history.back().parameter;
  return grown_over_stretch(
      history, 2.0, [&](const PeriodRecord& r) { return std::abs(r.parameter - p) <= tolerance; });
}

std::optional<HomoclinicApproach> unresolved_approach(const std::vector<PeriodRecord>& history) {
  if (history.size() < 2) return std::nullopt;
  return grown_over_stretch(history, kGrowth,
                            [](const PeriodRecord& r) { return r.trivial_error > kUnresolved; });
}

}  // namespace sympathy
