#include "sympathy/continuation/attractors.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "sympathy/continuation/equilibrium.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy {

OptionCheck AttractorOptions::validate() const {
  if (auto wrong = nested("orbit.", orbit.validate())) return wrong;
  if (auto wrong = nested("certificate.", certificate.validate())) return wrong;
  if (!(positive(match_tolerance) && match_tolerance < 0.5))
    return OptionProblem{"match_tolerance", "a number in (0, 0.5)"};
  if (!(positive(period_tolerance) && period_tolerance < 0.1))
    return OptionProblem{"period_tolerance", "a number in (0, 0.1)"};
  return std::nullopt;
}

bool same_orbit(const OdeSystem& system, const PeriodicOrbit& orbit,
                const OrbitNeighbourhood& neighbourhood, const AttractorOptions& options) {
  if (!(std::abs(orbit.period - neighbourhood.period) <=
        options.period_tolerance * neighbourhood.period))
    return false;
  // The certificate's section returns of `orbit`'s own motion (a certificate only reads it).
  ConvergenceCertificate returns(
      system, std::shared_ptr<const OrbitNeighbourhood>(&neighbourhood, [](auto*) {}));
  std::vector<double> times;
  for (int i = 0; i <= 500; ++i) times.push_back(1.25 * orbit.period * i / 500.0);
  try {
    Flow flow(system);
    flow.sample(orbit.state0, neighbourhood.parameters, 0.0, times,
                [&](double t, const Eigen::VectorXd& z) { returns.add(t, z); });
  } catch (const IntegrationError&) {
    return false;
  }
  const auto& d = returns.distances();
  return !d.empty() && *std::min_element(d.begin(), d.end()) <= options.match_tolerance;
}

bool same_rest(const Attractor& a, const Eigen::VectorXd& z) {
  return a.at_rest() && a.rest.size() == z.size() &&
         (a.rest - z).lpNorm<Eigen::Infinity>() <=
             1e-6 * std::max(1.0, z.lpNorm<Eigen::Infinity>());
}

bool stable_equilibrium(const Equilibrium& e) {
  const double size = std::max(1.0, e.eigenvalues.cwiseAbs().maxCoeff());
  return e.converged && e.eigenvalues.real().maxCoeff() < -1e-6 * size;
}

namespace {

// A stable orbit with its neighbourhood, or nothing: Newton from (z0, period) at p.
std::optional<Attractor> stable_orbit(const OdeSystem& system, const ParameterValues& p,
                                      const Eigen::VectorXd& z0, double period,
                                      const InvariantSubspace& subspace,
                                      const AttractorOptions& options) {
  Attractor a;
  try {
    a.orbit = solve_periodic_orbit(system, p, z0, period, subspace, options.orbit);
    if (!a.orbit.converged()) return std::nullopt;
    a.neighbourhood =
        std::make_shared<const OrbitNeighbourhood>(system, a.orbit, options.certificate);
  } catch (const IntegrationError&) {
    return std::nullopt;
  }
  if (!a.neighbourhood->eligible) return std::nullopt;
  return a;
}

bool known(const OdeSystem& system, const std::vector<Attractor>& list, const Attractor& a,
           const AttractorOptions& options) {
  return std::any_of(list.begin(), list.end(), [&](const Attractor& b) {
    if (a.at_rest() || b.at_rest()) return a.at_rest() && b.at_rest() && same_rest(b, a.rest);
    return same_orbit(system, a.orbit, *b.neighbourhood, options);
  });
}

}  // namespace

namespace {

// The attractors one branch holds at the value v of its parameter, appended to `found`: on every
// pair of neighbouring points whose parameters bracket v (each value once: a point exactly at v
// belongs to the pair it starts), not both unstable, `attractor(lo, hi, w)` (w: hi's weight)
// gives the one interpolated there, if any; those not already found, named by the branch (" (k)"
// where it holds more than one), with the nearer point's index. One scan for branches of orbits
// and of equilibria.
template <class Point, class Unstable, class Interpolated>
void add_branch_attractors(const OdeSystem& system, const std::vector<Point>& points, double v,
                           const std::string& name, const AttractorOptions& options,
                           Unstable unstable, Interpolated attractor,
                           std::vector<Attractor>& found) {
  std::vector<Attractor> on_this;
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    const Point& lo = points[i];
    const Point& hi = points[i + 1];
    if (!((lo.parameter - v) * (hi.parameter - v) < 0.0 || lo.parameter == v)) continue;
    if (unstable(lo) && unstable(hi)) continue;
    const double w =
        hi.parameter == lo.parameter ? 0.0 : (v - lo.parameter) / (hi.parameter - lo.parameter);
    std::optional<Attractor> a = attractor(lo, hi, w);
    if (!a || known(system, found, *a, options) || known(system, on_this, *a, options)) continue;
    a->branch = name;
    a->point = (w < 0.5 ? lo : hi).index;
    on_this.push_back(std::move(*a));
  }
  for (std::size_t k = 0; k < on_this.size(); ++k) {
    on_this[k].name = on_this.size() == 1 ? name : name + " (" + std::to_string(k + 1) + ")";
    found.push_back(std::move(on_this[k]));
  }
}

}  // namespace

std::vector<Attractor> attractors_on_branches(const OdeSystem& system, const ParameterValues& p,
                                              const std::vector<NamedBranch>& branches,
                                              const AttractorOptions& options) {
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  std::vector<Attractor> found;
  for (const auto& named : branches) {
    const Branch& b = *named.branch;
    add_branch_attractors(
        system, b.points, system.parameter(p, b.parameter), named.name, options,
        [](const ContinuationPoint& q) { return q.orbit.floquet.stability == Stability::Unstable; },
        [&](const ContinuationPoint& lo, const ContinuationPoint& hi,
            double w) -> std::optional<Attractor> {
          if (lo.orbit.state0.size() != hi.orbit.state0.size()) return std::nullopt;
          return stable_orbit(system, p, (1 - w) * lo.orbit.state0 + w * hi.orbit.state0,
                              (1 - w) * lo.orbit.period + w * hi.orbit.period,
                              (w < 0.5 ? lo : hi).orbit.subspace, options);
        },
        found);
  }
  return found;
}

std::vector<Attractor> attractors_at_rest_on_branches(const OdeSystem& system,
                                                      const ParameterValues& p,
                                                      const std::vector<NamedEquilibria>& branches,
                                                      const AttractorOptions& options) {
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  std::vector<Attractor> found;
  for (const auto& named : branches) {
    const EquilibriumBranch& b = *named.branch;
    add_branch_attractors(
        system, b.points, system.parameter(p, b.parameter), named.name, options,
        [](const EquilibriumPoint& q) { return q.unstable > 0; },
        [&](const EquilibriumPoint& lo, const EquilibriumPoint& hi,
            double w) -> std::optional<Attractor> {
          const Equilibrium e = solve_equilibrium(system, p, (1 - w) * lo.state + w * hi.state);
          if (!stable_equilibrium(e)) return std::nullopt;
          Attractor a;
          a.rest = e.state;
          return a;
        },
        found);
  }
  return found;
}

std::vector<Attractor> continue_attractors(const OdeSystem& system, const ParameterValues& p,
                                           const std::vector<Attractor>& previous,
                                           const AttractorOptions& options) {
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  std::vector<Attractor> continued;
  for (const auto& before : previous) {
    if (before.at_rest()) {
      const Equilibrium e = solve_equilibrium(system, p, before.rest);
      Attractor a = before;
      a.rest = e.state;
      if (stable_equilibrium(e) && !known(system, continued, a, options))
        continued.push_back(std::move(a));
      continue;
    }
    auto a = stable_orbit(system, p, before.orbit.state0, before.orbit.period,
                          before.orbit.subspace, options);
    if (!a || known(system, continued, *a, options)) continue;
    a->name = before.name;
    a->branch = before.branch;
    continued.push_back(std::move(*a));
  }
  return continued;
}

std::vector<Attractor> merge_attractors(const OdeSystem& system, std::vector<Attractor> on_branches,
                                        std::vector<Attractor> continued,
                                        const AttractorOptions& options) {
  std::vector<bool> renamed(on_branches.size(), false);
  std::vector<Attractor> merged;
  std::vector<Attractor> elsewhere;
  for (auto& c : continued) {
    bool matched = false;
    for (std::size_t i = 0; i < on_branches.size() && !matched; ++i)
      if (!renamed[i] && c.at_rest() == on_branches[i].at_rest() &&
          (c.at_rest() ? same_rest(on_branches[i], c.rest)
                       : same_orbit(system, c.orbit, *on_branches[i].neighbourhood, options))) {
        on_branches[i].name = c.name;
        renamed[i] = matched = true;
      }
    if (!matched) elsewhere.push_back(std::move(c));
  }
  // The names in use: the continued ones'; then each branch attractor keeps its own name where
  // it is free, else takes the next free " (k)" of its branch.
  std::set<std::string> used;
  for (std::size_t i = 0; i < on_branches.size(); ++i)
    if (renamed[i]) used.insert(on_branches[i].name);
  for (const auto& e : elsewhere) used.insert(e.name);
  for (std::size_t i = 0; i < on_branches.size(); ++i) {
    if (renamed[i]) continue;
    for (int k = 2; used.count(on_branches[i].name); ++k)
      on_branches[i].name = on_branches[i].branch + " (" + std::to_string(k) + ")";
    used.insert(on_branches[i].name);
  }
  for (auto& a : on_branches) merged.push_back(std::move(a));
  for (auto& a : elsewhere) merged.push_back(std::move(a));
  return merged;
}

}  // namespace sympathy
