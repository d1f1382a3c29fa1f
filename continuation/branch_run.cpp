#include "sympathy/continuation/branch_run.hpp"

#include <algorithm>
#include <map>
#include <stdexcept>

#include "sympathy/continuation/symmetry_reduction.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

std::string BranchProblem::problem_with(const OdeSystem& system) const {
  if (parameter < 0 || parameter >= system.parameter_count())
    return "parameter: expected the index of one of " + join(system.parameter_names());
  if (values.size() != system.parameter_values_size() || !values.allFinite())
    return "values: expected " + std::to_string(system.parameter_values_size()) +
           " finite parameter values";
  if (!std::isfinite(from) || !std::isfinite(to) || from == to)
    return "from, to: expected two different finite values";
  if (at && !(*at > std::min(from, to) && *at < std::max(from, to)))
    return "at " + format_double(*at) + ": expected a value between from and to";
  if (start_orbit) {
    if (!start_orbit->converged()) return "start_orbit: expected a converged orbit";
    if (start_orbit->parameters.size() != values.size())
      return "start_orbit: expected an orbit of this system, with its parameter values";
    const double v = system.parameter(start_orbit->parameters, parameter);
    if (!(std::abs(v - first_value()) <= 1e-12 * std::max(1.0, std::abs(first_value()))))
      return "start_orbit: an orbit at " + system.parameter_names()[parameter] + " = " +
             format_double(v) + "; expected one at the first value " + format_double(first_value());
  } else if (start_state.size() != system.dimension() || !start_state.allFinite()) {
    return "start_state: expected " + std::to_string(system.dimension()) + " finite values";
  } else if (start_period && !(*start_period > 0.0 && std::isfinite(*start_period))) {
    return "start_period: expected a positive period";
  } else if (!start_period && !system.autonomous() &&
             !(system.forcing_period(values.data()) > 0.0)) {
    return "start_period: expected the forcing's period (a periodically forced system that "
           "declares none)";
  }
  if (!system.autonomous()) {
    // The branch keeps the start's period: the continued parameter must not move the forcing's.
    const double declared = system.forcing_period(values.data());
    if (declared > 0.0) {
      const std::string name = system.parameter_names()[parameter];
      for (double v : {from, to, first_value()}) {
        const double at = system.forcing_period(system.with_parameter(values, parameter, v).data());
        if (!(std::abs(at - declared) <= 1e-14 * declared))
          return "parameter " + name + ": the forcing's period depends on it (" +
                 format_double(declared) + " at the given values, " + format_double(at) + " at " +
                 name + " = " + format_double(v) +
                 "); expected a parameter the forcing's period does not depend on";
      }
      if (!start_orbit && start_period && !(std::abs(*start_period - declared) <= 1e-12 * declared))
        return "start_period " + format_double(*start_period) + ": expected the forcing's period " +
               format_double(declared);
    }
  }
  return "";
}

namespace {

// Describes an orbit of the reduction as the whole orbit it stands for.
class LiftingDescriber final : public OrbitDescriber {
 public:
  LiftingDescriber(const OrbitDescriber& whole, const SymmetryReduction& reduction,
                   const InvariantSubspace& subspace, const FloquetOptions& options)
      : whole_(whole), reduction_(reduction), subspace_(subspace), options_(options) {}
  std::vector<Group> layout() const override { return whole_.layout(); }
  std::vector<double> describe(const PeriodicOrbit& orbit) const override {
    return whole_.describe(lift(orbit, reduction_, subspace_, options_));
  }

 private:
  const OrbitDescriber& whole_;
  const SymmetryReduction& reduction_;
  const InvariantSubspace& subspace_;
  const FloquetOptions& options_;
};

// The symmetry reduction of the whole branch, where the start's subspace has one that the
// parameter keeps: checked at both ends and at the start (a parameter of one metronome alone
// breaks the permutations as soon as it moves).
std::optional<SymmetryReduction> branch_reduction(const OdeSystem& system,
                                                  const BranchProblem& problem,
                                                  const ContinuationOptions& options) {
  if (!options.orbit.use_symmetry || problem.start_orbit || !problem.subspace.symmetry())
    return std::nullopt;
  std::optional<SymmetryReduction> r;
  for (double v : {problem.from, problem.to, problem.first_value()}) {
    const ParameterValues p = system.with_parameter(problem.values, problem.parameter, v);
    r = symmetry_reduction(system, p, problem.subspace);
    if (!r) return std::nullopt;
  }
  return r;
}

}  // namespace

Branch continue_branch(const OdeSystem& system, const BranchProblem& problem,
                       const ContinuationOptions& options, const ContinuationCallbacks& callbacks,
                       const OrbitDescriber* describer) {
  if (const std::string wrong = problem.problem_with(system); !wrong.empty())
    throw std::invalid_argument("branch problem: " + wrong);
  if (const auto wrong = options.validate())
    throw std::invalid_argument("continuation options: " + wrong->message());
  if (const auto r = branch_reduction(system, problem, options)) {
    // The branch of the reduced system, in the reduced subspace; everything it hands out lifted.
    BranchProblem reduced = problem;
    reduced.start_state = r->coordinates.restrict(problem.subspace.project(problem.start_state));
    reduced.subspace = r->subspace;
    const FloquetOptions& floquet = options.orbit.floquet;
    ContinuationCallbacks lifted;
    lifted.stop_requested = callbacks.stop_requested;
    if (callbacks.on_point)
      lifted.on_point = [&](const ContinuationPoint& p) {
        callbacks.on_point(lift(p, *r, problem.subspace, floquet));
      };
    if (callbacks.on_event)
      lifted.on_event = [&](const Bifurcation& e) { callbacks.on_event(lift(e, *r, floquet)); };
    const std::optional<LiftingDescriber> lifting =
        describer ? std::optional<LiftingDescriber>(std::in_place, *describer, *r, problem.subspace,
                                                    floquet)
                  : std::nullopt;
    Branch branch =
        continue_branch(*r->system, reduced, options, lifted, lifting ? &*lifting : nullptr);
    return lift(std::move(branch), *r, system, problem.subspace);
  }
  const Stopwatch clock;
  const double first = problem.first_value();
  const std::string parameter_name = system.parameter_names()[problem.parameter];

  Branch failed;
  failed.parameter_name = parameter_name;
  failed.parameter = problem.parameter;
  failed.state_names = system.state_names();
  failed.stop = StopReason::StartFailed;
  failed.options = options;
  failed.start_values = problem.values;
  PeriodicOrbit orbit;
  if (problem.start_orbit) {
    orbit = *problem.start_orbit;
  } else {
    const ParameterValues values = system.with_parameter(problem.values, problem.parameter, first);
    orbit = problem.start_period
                ? solve_periodic_orbit(system, values, problem.start_state, *problem.start_period,
                                       problem.subspace, options.orbit)
                : find_periodic_orbit(system, values, problem.start_state, problem.subspace,
                                      options.orbit);
    failed.flow = orbit.flow;
  }
  if (!orbit.converged()) {
    failed.stop_reason = "no periodic orbit from start '" + problem.start_name + "' at " +
                         parameter_name + " = " + format_double(first) + ": " + orbit.newton.reason;
    failed.seconds = clock.seconds();
    return failed;
  }

  ContinuationOptions bounded = options;
  bounded.lower = std::min(problem.from, problem.to);
  bounded.upper = std::max(problem.from, problem.to);
  // Each point described once, as it is found; kept by its index along the joined branch.
  std::map<int, std::vector<double>> descriptions;
  int index_sign = +1;  // -1 on the backward part of a two-way run
  ContinuationCallbacks inner;
  inner.stop_requested = callbacks.stop_requested;
  // The callbacks see the joined branch: the backward run's copy of the start is not reported
  // again, and its events name the point before them along the joined branch (join_branches).
  inner.on_event = [&](const Bifurcation& event) {
    if (!callbacks.on_event) return;
    if (index_sign > 0) return callbacks.on_event(event);
    Bifurcation e = event;
    e.after_point = -(e.after_point + 1);
    callbacks.on_event(e);
  };
  inner.on_point = [&](const ContinuationPoint& point) {
    if (index_sign < 0 && point.index == 0) return;  // the start, reported by the forward run
    ContinuationPoint p = point;
    p.index *= index_sign;
    if (describer) p.description = describer->describe(p.orbit);
    if (callbacks.on_point) callbacks.on_point(p);
    descriptions[p.index] = std::move(p.description);
  };
  Continuation continuation(system, problem.parameter, bounded);
  const int toward = problem.to >= first ? +1 : -1;
  Branch forward = continuation.run(orbit, toward, inner);
  Branch branch;
  const bool interrupted = callbacks.stop_requested && callbacks.stop_requested();
  if (problem.at && !interrupted && forward.started()) {
    index_sign = -1;
    // The other way from the same orbit: its stiffness as the forward run measured it (each run
    // chooses its integrator, and would measure it again).
    if (!orbit.stiffness) orbit.stiffness = forward.stiffness;
    branch = join_branches(continuation.run(orbit, -toward, inner), std::move(forward));
  } else {
    branch = std::move(forward);
  }
  for (auto& p : branch.points) {
    auto it = descriptions.find(p.index);
    if (it != descriptions.end()) p.description = std::move(it->second);
  }
  if (describer) describe_events(branch, system, *describer, problem.values, orbit.subspace);
  for (auto& e : branch.events) e.samples = PeriodSamples{};
  if (!problem.start_orbit) branch.flow += orbit.flow;  // the start's transient and Newton
  branch.seconds = clock.seconds();
  return branch;
}

void describe_events(Branch& branch, const OdeSystem& system, const OrbitDescriber& describer,
                     const ParameterValues& values, const InvariantSubspace& subspace) {
  for (auto& e : branch.events) {
    // The located orbit, for the describer: its samples from location (or, where they are not
    // of this state and period, one plain integration of the period).
    PeriodicOrbit located;
    located.state0 = e.state0;
    located.period = e.period;
    located.parameters = system.with_parameter(values, branch.parameter, e.parameter);
    located.subspace = subspace;
    located.samples = std::move(e.samples);
    e.samples = PeriodSamples{};
    e.description = describer.describe(located);
  }
}

}  // namespace sympathy
