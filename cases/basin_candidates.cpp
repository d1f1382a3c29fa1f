#include "sympathy/cases/basin_candidates.hpp"

#include <cmath>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy {

namespace {

constexpr int kAngleSamples = 2000;  // per period

}  // namespace

std::vector<double> BasinCandidate::angles_at(double s) const {
  const double phase = std::fmod(s / orbit.period, 1.0);
  const double x = (phase < 0.0 ? phase + 1.0 : phase) * angles.size();
  const std::size_t i = static_cast<std::size_t>(x) % angles.size();
  const std::size_t j = (i + 1) % angles.size();
  const double w = x - std::floor(x);
  std::vector<double> a(angles[i].size());
  for (std::size_t k = 0; k < a.size(); ++k) a[k] = (1 - w) * angles[i][k] + w * angles[j][k];
  return a;
}

std::vector<BasinCandidate> basin_candidates(const MetronomeModel& model,
                                             const std::vector<BasinCandidateStart>& starts,
                                             const OrbitOptions& orbit,
                                             const CertificateOptions& certificate,
                                             const std::vector<std::vector<int>>& groups,
                                             const SyncClassifierOptions& classifier, double dt) {
  const ParameterValues p = model.default_parameters();
  const int pendula = model.metronome_count();
  std::vector<BasinCandidate> found;
  for (const auto& start : starts) {
    BasinCandidate c;
    c.start = start.name;
    try {
      c.orbit = find_periodic_orbit(model, p, start.state, start.subspace, orbit);
    } catch (const IntegrationError&) {
      continue;
    }
    if (!c.orbit.converged()) continue;
    c.neighbourhood = std::make_shared<const OrbitNeighbourhood>(model, c.orbit, certificate);
    if (!c.neighbourhood->eligible) continue;
    // Its class: the classifier over its own motion, a window and a few periods long.
    Flow flow(model);
    SyncClassifier classify(groups, classifier);
    std::vector<double> times;
    for (double t = 0.0; t <= classifier.window + 3 * c.orbit.period + dt; t += dt)
      times.push_back(t);
    std::vector<double> angles(pendula);
    flow.sample(c.orbit.state0, p, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
      for (int i = 0; i < pendula; ++i) angles[i] = z[model.angle_index(i)];
      classify.add(t, angles);
    });
    c.name = classify.classify().name;
    bool again = false;
    for (const auto& other : found)
      again = again || (other.name == c.name &&
                        std::abs(other.orbit.period - c.orbit.period) <= 1e-6 * c.orbit.period);
    if (again) continue;
    times.clear();
    for (int k = 0; k < kAngleSamples; ++k) times.push_back(c.orbit.period * k / kAngleSamples);
    flow.sample(c.orbit.state0, p, 0.0, times, [&](double, const Eigen::VectorXd& z) {
      for (int i = 0; i < pendula; ++i) angles[i] = z[model.angle_index(i)];
      c.angles.push_back(angles);
    });
    found.push_back(std::move(c));
  }
  return found;
}

}  // namespace sympathy
