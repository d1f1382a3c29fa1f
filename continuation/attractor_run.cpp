#include "sympathy/continuation/attractor_run.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>

#include "sympathy/continuation/equilibrium.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

OptionCheck AttractorRunOptions::validate() const {
  if (!positive(t_end)) return OptionProblem{"t_end", "a positive number"};
  if (!(positive(dt) && dt <= t_end && t_end / dt <= kMaxSamples))
    return OptionProblem{"dt", "a positive number up to t_end, at most 1e7 samples"};
  if (auto wrong = nested("flow.", flow.validate())) return wrong;
  return nested("attractors.", attractors.validate());
}

std::string to_string(Fate f) {
  switch (f) {
    case Fate::Certified:
      return "certified";
    case Fate::Reached:
      return "reached";
    case Fate::NewOrbit:
      return "new orbit";
    case Fate::Equilibrium:
      return "equilibrium";
    case Fate::Torus:
      return "torus";
    case Fate::Unresolved:
      return "unresolved";
    case Fate::Failed:
      return "failed";
  }
  return "?";
}

namespace {

// Whether the motion from the run's end circles `orbit` on a torus: the orbit's largest
// nontrivial multiplier is one of a complex pair outside the unit circle (a torus born at its NS
// point surrounds it), and over kTorusReturns returns to its section (after kTorusSettle), each
// one period after the last, the motion stays at a steady distance from the orbit's point
// (below kTorusDistance in the eigen-coordinates, the nearest at least a tenth of the farthest:
// not converging onto the orbit, not leaving it). Crossings of the section count as returns within
// kTorusReach of the point in the scaled states (a state still on the orbit, as the platform on
// the anti-phase orbit, has a scale of 1e-3 of the largest, and the torus moves it: the row
// setup's torus at k = 55 N/m lies 0.7 to 1.4 from the anti-phase orbit in the eigen-coordinates
// and further in that state; the section's other crossing, on the orbit's far side, runs the
// other way). Its rotation number: the mean turn of that pair's coordinate from one return to the
// next, in turns, in [0, 1) (on the normal form's torus exactly the pair's argument over 2 pi).
// Sets fate.rotation_number where true.
constexpr int kTorusReturns = 60;
constexpr int kTorusSettle = 10;
constexpr double kTorusReach = 10.0;
constexpr double kTorusDistance = 3.0;

bool on_torus(const OdeSystem& system, const ParameterValues& p,
              const std::shared_ptr<const OrbitNeighbourhood>& orbit,
              const AttractorRunOptions& options, AttractorFate& fate) {
  const Eigen::VectorXcd& mu = orbit->multipliers;
  if (mu.size() == 0) return false;
  Eigen::Index lead = 0;
  mu.cwiseAbs().maxCoeff(&lead);
  if (!(std::abs(mu[lead]) > 1.0 && std::abs(mu[lead].imag()) > 1e-9 * std::abs(mu[lead])))
    return false;
  ConvergenceCertificate returns(system, orbit, kTorusReach);
  std::vector<double> turns;
  std::complex<double> previous;
  std::size_t seen = 0;
  const double dt = std::min(options.dt, orbit->period / 20.0);
  std::vector<double> times;
  for (double t = 0.0; t <= (kTorusReturns + kTorusSettle + 1.5) * orbit->period; t += dt)
    times.push_back(t);
  Flow flow(system, options.flow);
  flow.sample_until(fate.end_state, p, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
    returns.add(t, z);
    if (returns.distances().size() > seen) {
      seen = returns.distances().size();
      const std::complex<double> c = returns.last_coordinates()[lead];
      if (seen > static_cast<std::size_t>(kTorusSettle) && std::abs(previous) > 0.0 &&
          std::abs(c) > 0.0)
        turns.push_back(std::arg(c / previous));
      previous = c;
    }
    return turns.size() >= static_cast<std::size_t>(kTorusReturns);
  });
  const auto& d = returns.distances();
  if (turns.size() < static_cast<std::size_t>(kTorusReturns)) return false;
  const auto [low, high] = std::minmax_element(d.begin() + kTorusSettle, d.end());
  if (!(*high < kTorusDistance && *low >= 0.1 * *high)) return false;
  // Every return counted: one period after the last (within half a period), none skipped.
  const auto& t = returns.return_times();
  for (std::size_t k = 1; k < t.size(); ++k)
    if (std::abs(t[k] - t[k - 1] - orbit->period) > 0.5 * orbit->period) return false;
  double mean = 0.0;
  for (double a : turns) mean += a;
  mean /= static_cast<double>(turns.size());
  const double r = mean / (2.0 * std::acos(-1.0));
  fate.rotation_number = r - std::floor(r);
  return true;
}

// Where a run that was not certified ended: first whether at rest, near a stable equilibrium
// (Newton on f = 0 from the end converges within 1e-3 of it, relative to the state's size, and
// every eigenvalue's real part is below -1e-6 times the largest |lambda|: a decaying focus's
// spiral returns to a section too, so it is asked before any period); else Newton on the
// shooting problem from the end, with the period of its first return to the section through it.
void identify_end(const OdeSystem& system, const ParameterValues& p,
                  const std::vector<Attractor>& attractors, const AttractorRunOptions& options,
                  AttractorFate& fate) {
  const AttractorOptions& ao = options.attractors;
  const double scale = std::max(1.0, fate.end_state.lpNorm<Eigen::Infinity>());
  const Equilibrium e = solve_equilibrium(system, p, fate.end_state);
  if (e.converged && (e.state - fate.end_state).lpNorm<Eigen::Infinity>() <= 1e-3 * scale) {
    if (stable_equilibrium(e)) {
      fate.fate = Fate::Equilibrium;
      fate.equilibrium_state = e.state;
      for (std::size_t i = 0; i < attractors.size() && fate.attractor < 0; ++i)
        if (same_rest(attractors[i], e.state)) fate.attractor = static_cast<int>(i);
      return;
    }
    if (e.unstable > 0 && (e.state - fate.end_state).lpNorm<Eigen::Infinity>() <= 1e-6 * scale) {
      fate.note =
          "at an unstable equilibrium (" + std::to_string(e.unstable) + " unstable eigenvalues)";
      return;
    }
  }
  Flow flow(system, ao.orbit.transient_flow);
  // Looked for up to the orbit options' longest period or twice the attractors' longest, if that
  // is longer (a system slower than the metronomes' 0.6 s).
  double longest = ao.orbit.max_period;
  for (const auto& a : attractors) longest = std::max(longest, 2.0 * a.orbit.period);
  const double period =
      estimate_period(flow, p, fate.end_state, longest, std::min(options.dt, 0.01));
  if (period <= 0.0) {
    fate.note = "no return within " + format_number(longest) + " and not at rest";
    return;
  }
  PeriodicOrbit orbit;
  try {
    orbit = solve_periodic_orbit(system, p, fate.end_state, period, InvariantSubspace{}, ao.orbit);
  } catch (const IntegrationError& e) {
    fate.note = std::string("Newton from the end: ").append(e.what());
    return;
  }
  if (!orbit.converged()) {
    fate.note = "not near a periodic orbit (Newton from the end: " + orbit.newton.reason + ")";
    return;
  }
  for (std::size_t i = 0; i < attractors.size(); ++i)
    if (!attractors[i].at_rest() && same_orbit(system, orbit, *attractors[i].neighbourhood, ao)) {
      fate.fate = Fate::Reached;
      fate.attractor = static_cast<int>(i);
      return;
    }
  const auto neighbourhood =
      std::make_shared<const OrbitNeighbourhood>(system, orbit, ao.certificate);
  if (!neighbourhood->eligible && on_torus(system, p, neighbourhood, options, fate)) {
    fate.fate = Fate::Torus;
    fate.orbit = std::move(orbit);
    return;
  }
  if (!neighbourhood->eligible) {
    fate.note = "near an orbit of period " + std::to_string(orbit.period) +
                " that is not stable with the margin (largest multiplier " +
                std::to_string(orbit.floquet.max_modulus) + ")";
    return;
  }
  fate.fate = Fate::NewOrbit;
  fate.orbit = std::move(orbit);
  fate.neighbourhood = neighbourhood;
}

}  // namespace

std::optional<AttractorFate> run_to_attractor(const OdeSystem& system, const ParameterValues& p,
                                              const Eigen::VectorXd& start,
                                              const std::vector<Attractor>& attractors,
                                              const AttractorRunOptions& options,
                                              const std::atomic<bool>* stop) {
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  // A certificate per attractor, with its index: an orbit's, an equilibrium's.
  std::vector<ConvergenceCertificate> certificates;
  std::vector<int> certified_index;
  std::vector<RestCertificate> rests;
  std::vector<int> rest_index;
  for (std::size_t i = 0; i < attractors.size(); ++i) {
    if (!attractors[i].at_rest()) {
      certificates.emplace_back(system, attractors[i].neighbourhood);
      certified_index.push_back(static_cast<int>(i));
    } else if (system.autonomous()) {
      rests.emplace_back(system, p, attractors[i].rest, options.attractors.certificate);
      rest_index.push_back(static_cast<int>(i));
    }
  }
  const std::vector<double> times = sample_times(options.t_end, options.dt);
  AttractorFate fate;
  fate.end_state = start;
  bool stopped = false;
  try {
    Flow flow(system, options.flow);
    stopped = flow.sample_until(start, p, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
      fate.end_state = z;
      fate.stopped_at = t;
      for (std::size_t c = 0; c < certificates.size() && fate.attractor < 0; ++c)
        if (certificates[c].add(t, z)) fate.attractor = certified_index[c];
      for (std::size_t c = 0; c < rests.size() && fate.attractor < 0; ++c)
        if (rests[c].add(z)) fate.attractor = rest_index[c];
      return (stop && stop->load()) || fate.attractor >= 0;
    });
  } catch (const IntegrationError& e) {
    fate.fate = Fate::Failed;
    fate.note = e.what();
    return fate;
  }
  if (fate.attractor >= 0) {
    fate.fate = Fate::Certified;
    return fate;
  }
  if (stopped) return std::nullopt;
  try {
    identify_end(system, p, attractors, options, fate);
  } catch (const IntegrationError& e) {
    fate.fate = Fate::Unresolved;
    fate.note = std::string("identifying the end: ").append(e.what());
  }
  return fate;
}

namespace {

// " (DESCRIPTION)" of the smallest of `symmetries` that z lies in (an orbit lies in an invariant
// subspace where one of its points does), "" where none.
std::string symmetry_of(const Eigen::VectorXd& z,
                        const std::vector<InvariantSubspace>& symmetries) {
  const double tolerance = 1e-8 * std::max(1.0, z.lpNorm<Eigen::Infinity>());
  const InvariantSubspace* kept = nullptr;
  long smallest = z.size() + 1;
  for (const auto& s : symmetries) {
    if (s.is_whole_space() || s.description().empty()) continue;
    const long size = s.coordinates(static_cast<int>(z.size())).size();
    if (size < smallest && (z - s.project(z)).lpNorm<Eigen::Infinity>() <= tolerance) {
      kept = &s;
      smallest = size;
    }
  }
  return kept ? " (" + kept->description() + ")" : "";
}

}  // namespace

std::vector<Attractor> name_new_attractors(const OdeSystem& system,
                                           std::vector<AttractorFate>& fates,
                                           const AttractorOptions& options, int offset, int first,
                                           const std::vector<InvariantSubspace>& symmetries) {
  std::vector<Attractor> found;
  for (auto& fate : fates) {
    if (fate.fate == Fate::Equilibrium && fate.attractor < 0) {
      // A stable equilibrium none of the attractors is: "new k (at rest)", once.
      int index = -1;
      for (std::size_t i = 0; i < found.size() && index < 0; ++i)
        if (same_rest(found[i], fate.equilibrium_state)) index = static_cast<int>(i);
      if (index < 0) {
        Attractor a;
        const std::string kept = symmetry_of(fate.equilibrium_state, symmetries);
        a.name = "new " + std::to_string(first + static_cast<int>(found.size())) + " (at rest" +
                 (kept.empty() ? "" : ", " + kept.substr(2, kept.size() - 3)) + ")";
        a.rest = fate.equilibrium_state;
        index = static_cast<int>(found.size());
        found.push_back(std::move(a));
      }
      fate.attractor = offset + index;
      continue;
    }
    if (fate.fate != Fate::NewOrbit || !fate.orbit) continue;
    int index = -1;
    for (std::size_t i = 0; i < found.size() && index < 0; ++i)
      if (!found[i].at_rest() && same_orbit(system, *fate.orbit, *found[i].neighbourhood, options))
        index = static_cast<int>(i);
    if (index < 0) {
      Attractor a;
      a.name = "new " + std::to_string(first + static_cast<int>(found.size())) +
               symmetry_of(fate.orbit->state0, symmetries);
      a.orbit = *fate.orbit;
      a.neighbourhood = fate.neighbourhood ? fate.neighbourhood
                                           : std::make_shared<const OrbitNeighbourhood>(
                                                 system, a.orbit, options.certificate);
      index = static_cast<int>(found.size());
      found.push_back(std::move(a));
    }
    fate.attractor = offset + index;
  }
  return found;
}

}  // namespace sympathy
