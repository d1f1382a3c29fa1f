#include "sympathy/core/oscillation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sympathy {

OscillationAnalyzer::OscillationAnalyzer(std::vector<int> phase_components,
                                         std::vector<int> amplitude_components, double window)
    : phase_components_(std::move(phase_components)),
      amplitude_components_(std::move(amplitude_components)),
      window_(window),
      crossings_(phase_components_.size()) {}

void OscillationAnalyzer::add(double t, const Eigen::VectorXd& z) {
  if (has_previous_) {
    for (std::size_t k = 0; k < phase_components_.size(); ++k) {
      const double a = z_previous_[phase_components_[k]], b = z[phase_components_[k]];
      if (a < 0.0 && b >= 0.0)
        crossings_[k].push_back(t_previous_ + (t - t_previous_) * (-a) / (b - a));
    }
  }
  has_previous_ = true;
  t_previous_ = t;
  z_previous_ = z;
  Eigen::VectorXd kept(amplitude_components_.size());
  for (std::size_t k = 0; k < amplitude_components_.size(); ++k)
    kept[k] = z[amplitude_components_[k]];
  recent_.emplace_back(t, std::move(kept));
  while (!recent_.empty() && recent_.front().first < t - window_) recent_.pop_front();
}

OscillationSummary OscillationAnalyzer::summary() const {
  OscillationSummary s;
  const std::size_t na = amplitude_components_.size();
  s.amplitudes.assign(na, 0.0);
  if (!recent_.empty()) {
    Eigen::VectorXd lo = recent_.front().second, hi = lo;
    for (const auto& [t, v] : recent_) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    for (std::size_t k = 0; k < na; ++k) s.amplitudes[k] = 0.5 * (hi[k] - lo[k]);
  }
  if (phase_components_.empty() || recent_.empty()) return s;
  const double t_start = recent_.front().first;
  const auto& ref = crossings_[0];
  std::vector<double> in_window;
  for (double c : ref)
    if (c >= t_start) in_window.push_back(c);
  s.cycles = static_cast<int>(in_window.size());
  if (in_window.size() < 2) return s;
  const double period = (in_window.back() - in_window.front()) / (in_window.size() - 1);
  s.frequency = 1.0 / period;
  const double t_ref = in_window.back();
  for (std::size_t k = 1; k < phase_components_.size(); ++k) {
    const auto& ck = crossings_[k];
    if (ck.empty()) {
      s.phase_differences.push_back(std::nan(""));
      continue;
    }
    // The crossing of component k nearest to the reference's last one.
    auto nearest = *std::min_element(ck.begin(), ck.end(), [&](double a, double b) {
      return std::abs(a - t_ref) < std::abs(b - t_ref);
    });
    // Component k leads when it crosses earlier: its phase is ahead.
    double phase = 2.0 * std::numbers::pi * (t_ref - nearest) / period;
    phase = std::remainder(phase, 2.0 * std::numbers::pi);
    if (phase <= -std::numbers::pi) phase += 2.0 * std::numbers::pi;
    s.phase_differences.push_back(phase);
  }
  return s;
}

}  // namespace sympathy
