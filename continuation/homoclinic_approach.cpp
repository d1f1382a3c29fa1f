#include "sympathy/continuation/homoclinic_approach.hpp"

#include <algorithm>
#include <cmath>

namespace sympathy {

std::optional<HomoclinicApproach> homoclinic_approach(
    const std::vector<std::pair<double, double>>& history, double tolerance) {
  if (history.size() < 3) return std::nullopt;
  const auto& [p, period] = history.back();
  if (!(period > history[history.size() - 2].second)) return std::nullopt;  // not growing
  HomoclinicApproach h;
  h.parameter = p;
  h.to_period = period;
  h.from_period = period;
  for (auto it = history.rbegin(); it != history.rend(); ++it) {
    const double spread = std::abs(it->first - p);
    if (spread > tolerance) break;
    h.parameter_spread = std::max(h.parameter_spread, spread);
    h.from_period = std::min(h.from_period, it->second);
  }
  if (period >= 2.0 * h.from_period) return h;
  return std::nullopt;
}

std::optional<HomoclinicApproach> unresolved_approach(
    const std::vector<std::pair<double, double>>& history, const std::vector<double>& errors) {
  if (history.size() < 2 || errors.size() != history.size()) return std::nullopt;
  const auto& [p, period] = history.back();
  if (!(period > history[history.size() - 2].second)) return std::nullopt;  // not growing
  HomoclinicApproach h;
  h.parameter = p;
  h.to_period = period;
  h.from_period = period;
  for (std::size_t k = history.size(); k-- > 0;) {
    if (!(errors[k] > kUnresolved)) break;
    h.from_period = std::min(h.from_period, history[k].second);
    h.parameter_spread = std::max(h.parameter_spread, std::abs(history[k].first - p));
  }
  if (period >= kGrowth * h.from_period) return h;
  return std::nullopt;
}

}  // namespace sympathy
