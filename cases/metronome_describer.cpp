#include "sympathy/cases/metronome_describer.hpp"

#include <cmath>
#include <numbers>

#include "sympathy/core/flow.hpp"

namespace sympathy {

MetronomeDescriber::Report MetronomeDescriber::report(const PeriodicOrbit& orbit) const {
  Report r;
  const int positions = model_.dimension() / 2;
  const int pendula = model_.metronome_count();
  r.amplitudes.assign(positions, 0.0);
  r.phase_differences.assign(pendula - 1, std::nan(""));
  if (!(orbit.period > 0.0)) return r;
  Eigen::VectorXd lo = orbit.state0, hi = orbit.state0, previous = orbit.state0;
  std::vector<double> crossing(pendula, std::nan(""));
  double t_previous = 0.0;
  try {
    sample_period(model_, orbit, [&](double t, const Eigen::VectorXd& z) {
      lo = lo.cwiseMin(z);
      hi = hi.cwiseMax(z);
      for (int i = 0; i < pendula; ++i) {
        const int c = model_.angle_index(i);
        if (t > 0.0 && previous[c] < 0.0 && z[c] >= 0.0 && std::isnan(crossing[i]))
          crossing[i] = t_previous + (t - t_previous) * (-previous[c]) / (z[c] - previous[c]);
      }
      previous = z;
      t_previous = t;
    });
  } catch (const IntegrationError&) {
    return r;  // amplitudes unknown; the orbit's own figures still stand
  }
  for (int i = 0; i < positions; ++i) r.amplitudes[i] = 0.5 * (hi[i] - lo[i]);
  for (int i = 1; i < pendula; ++i) {
    if (std::isnan(crossing[0]) || std::isnan(crossing[i])) continue;
    double phase = 2.0 * std::numbers::pi * (crossing[0] - crossing[i]) / orbit.period;
    phase = std::remainder(phase, 2.0 * std::numbers::pi);
    if (phase <= -std::numbers::pi) phase += 2.0 * std::numbers::pi;
    r.phase_differences[i - 1] = phase;
  }
  return r;
}

std::vector<OrbitDescriber::Group> MetronomeDescriber::layout() const {
  const auto names = model_.state_names();
  Group amplitudes{"amplitudes", "amp_", {}}, phases{"phase_differences", "phase_", {}};
  for (int i = 0; i < model_.dimension() / 2; ++i) amplitudes.labels.push_back(names[i]);
  for (int i = 1; i < model_.metronome_count(); ++i)
    phases.labels.push_back("th" + std::to_string(i + 1));
  return {amplitudes, phases};
}

std::vector<double> MetronomeDescriber::describe(const PeriodicOrbit& orbit) const {
  Report r = report(orbit);
  r.amplitudes.insert(r.amplitudes.end(), r.phase_differences.begin(), r.phase_differences.end());
  return r.amplitudes;
}

}  // namespace sympathy
