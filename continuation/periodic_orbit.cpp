#include "sympathy/continuation/periodic_orbit.hpp"

#include "sympathy/continuation/accuracy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "stiffness_choice.hpp"
#include "sympathy/continuation/symmetry_reduction.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/hybrid_system.hpp"
#include "sympathy/core/linear_solve.hpp"
#include "sympathy/core/reduced_system.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

// The default preset (accuracy.hpp): the same options whether a computation came in through the
// library, the command line or Python.
OrbitOptions::OrbitOptions() {
  apply_accuracy(Accuracy::Default, *this);
}

OptionCheck NewtonOptions::validate() const {
  if (!positive(residual_tolerance))
    return OptionProblem{"residual_tolerance", "a positive number"};
  if (!(rtol_factor >= 1.0 && std::isfinite(rtol_factor)))
    return OptionProblem{"rtol_factor", "a number of at least 1"};
  if (max_iterations < 1) return OptionProblem{"max_iterations", "a positive integer"};
  if (max_halvings < 0) return OptionProblem{"max_halvings", "a non-negative integer"};
  if (!(positive(rank_tolerance) && rank_tolerance < 1.0))
    return OptionProblem{"rank_tolerance", "a number in (0, 1)"};
  return std::nullopt;
}

OptionCheck OrbitOptions::validate() const {
  if (!non_negative(transient))
    return OptionProblem{"transient", "a non-negative number of seconds"};
  if (!(non_negative(settle_tolerance) && settle_tolerance < 1.0))
    return OptionProblem{"settle_tolerance", "0 (the whole transient) or a number in (0, 1)"};
  if (!(non_negative(early_newton_below) && early_newton_below < 1.0))
    return OptionProblem{"early_newton_below", "0 (never) or a number in (0, 1)"};
  if (!positive(max_period)) return OptionProblem{"max_period", "a positive number of seconds"};
  if (auto p = nested("shooting.", shooting.validate())) return p;
  if (auto p = nested("newton.", newton.validate())) return p;
  if (auto p = nested("floquet.", floquet.validate())) return p;
  return nested("transient_flow.", transient_flow.validate());
}

std::string to_string(NewtonOutcome o) {
  switch (o) {
    case NewtonOutcome::Converged:
      return "converged";
    case NewtonOutcome::NoiseFloor:
      return "noise floor";
    case NewtonOutcome::NotRun:
      return "not run";
    case NewtonOutcome::IterationLimit:
      return "iteration limit";
    case NewtonOutcome::NoDescent:
      return "no descent";
    case NewtonOutcome::Vanishing:
      return "vanishing amplitude";
    case NewtonOutcome::NonFiniteStep:
      return "non-finite step";
    case NewtonOutcome::GuessNotIntegrable:
      return "guess not integrable";
    case NewtonOutcome::TransientFailed:
      return "transient failed";
    case NewtonOutcome::NoPeriod:
      return "no period";
  }
  return "?";
}

namespace {

// y - z with the system's angles' differences taken to (-pi, pi]: how far apart two states are
// on the circle (a rotating pendulum is back where it was after a turn).
Eigen::VectorXd state_difference(const OdeSystem& system, const Eigen::VectorXd& y,
                                 const Eigen::VectorXd& z) {
  Eigen::VectorXd d = y - z;
  for (int i : system.angle_states()) d[i] = std::remainder(d[i], 2.0 * M_PI);
  return d;
}

// z with its angles taken to (-pi, pi]: the same point of the state space.
Eigen::VectorXd wrap_angles(const OdeSystem& system, Eigen::VectorXd z) {
  for (int i : system.angle_states()) z[i] = std::remainder(z[i], 2.0 * M_PI);
  return z;
}

// The largest magnitude of a state's component.
double state_size(const Eigen::VectorXd& z) {
  return std::max(z.cwiseAbs().maxCoeff(), 1e-300);
}

// One period of the motion from z: how far it came back (its return's distance, angles on the
// circle) and the motion's own size over the period, the largest half range of a state (at the
// integrator's steps: the same integration as a plain advance, step for step). A return is
// measured against the smaller of that amplitude and the state's size: against the state's
// size alone, a slowly growing spiral about an equilibrium far from the origin looked settled
// (AUTO's chu at alpha = 6.9, about its equilibrium x = 1.5, moved by 0.1% of the state but 0.9%
// of its own amplitude); for a motion about the origin (the metronomes) the state's size is the
// smaller, and its starts are as they were.
struct Return {
  Eigen::VectorXd later;  // the state a period on
  double moved = 0.0;
  double size = 0.0;
};

Return one_return(Flow& flow, const ParameterValues& p, const Eigen::VectorXd& z, double period,
                  const InvariantSubspace& subspace) {
  Eigen::VectorXd low = z, high = z;
  Return r;
  r.later = subspace.project(flow.advance_observing_steps(
      z, p, 0.0, period, [&](double, double, const Eigen::VectorXd& y) {
        low = low.cwiseMin(y);
        high = high.cwiseMax(y);
      }));
  for (int i : flow.system().angle_states()) low[i] = high[i] = 0.0;  // a turn is no size
  r.size = std::max(0.5 * (high - low).maxCoeff(), 1e-300);
  r.moved = state_difference(flow.system(), r.later, z).cwiseAbs().maxCoeff();
  return r;
}

double inf_norm(const Eigen::VectorXd& v) {
  return v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
}

// Every segment state of the unknowns projected into the subspace (the period untouched).
Eigen::VectorXd project_unknowns(const InvariantSubspace& subspace, Eigen::VectorXd x, int n,
                                 int m) {
  if (subspace.is_whole_space()) return x;
  for (int j = 0; j < m; ++j) x.segment(j * n, n) = subspace.project(x.segment(j * n, n));
  return x;
}

// Whether Newton, tried where the transient had reached `z`, found the orbit the transient was
// approaching: converged within a tenth of the state's size of z, and stable in the space the
// transient runs in (the multipliers that break the orbit's symmetry act across it).
bool approached(const OdeSystem& system, const PeriodicOrbit& orbit, const Eigen::VectorXd& z,
                const FloquetOptions& floquet) {
  if (!orbit.converged()) return false;
  const double size = std::max(z.cwiseAbs().maxCoeff(), 1e-300);
  if (state_difference(system, orbit.state0, z).cwiseAbs().maxCoeff() > 0.1 * size) return false;
  for (const Multiplier& m : orbit.floquet.multipliers) {
    if (m.trivial || m.structural || m.symmetry == SymmetryKind::Breaking) continue;
    if (!(std::abs(m.value) < 1.0 - floquet.stability_tolerance)) return false;
  }
  return true;
}

}  // namespace

FloquetAnalysis shooting_floquet(const ShootingProblem& problem,
                                 const ShootingProblem::Evaluation& e, const Eigen::VectorXd& z0,
                                 int family_dimension, const FloquetOptions& options,
                                 const InvariantSubspace& subspace) {
  const Eigen::VectorXd f =
      problem.autonomous() ? problem.system().rhs(0.0, z0, e.parameters) : Eigen::VectorXd();
  const Eigen::MatrixXd family =
      family_dimension > 0
          ? Eigen::MatrixXd(
                null_vectors(problem.jacobian(e), family_dimension).topRows(problem.dimension()))
          : Eigen::MatrixXd();
  FloquetAnalysis a = analyze_floquet(e.transitions, f, family, options);
  if (!subspace.is_whole_space()) {
    const auto bases = subspace.bases(problem.dimension());
    label_symmetry(a, e.transitions, bases.inside, bases.across);
  }
  return a;
}

PeriodicOrbit solve_periodic_orbit(const OdeSystem& system, const ParameterValues& p,
                                   const Eigen::VectorXd& z0, double period,
                                   const InvariantSubspace& subspace, const OrbitOptions& options) {
  const Stopwatch started;
  system.check_parameters(p);
  if (const auto problem = options.validate())
    throw std::invalid_argument("orbit options: " + problem->message());
  if (options.use_symmetry)
    if (const auto r = symmetry_reduction(system, p, subspace)) {
      PeriodicOrbit orbit =
          solve_periodic_orbit(*r->system, p, r->coordinates.restrict(subspace.project(z0)), period,
                               r->subspace, options);
      orbit = lift(std::move(orbit), *r, subspace, options.floquet);
      orbit.seconds = started.seconds();
      return orbit;
    }
  // The integrator: the method as set, or BDF where the guess's period is stiff for it (measured
  // over one period at the shooting's tolerance by two plain runs: 7 ms, about 4% of the row
  // setup's orbit at the default). A guess that cannot be integrated is left to Newton's first
  // evaluation to report.
  ShootingOptions shooting = options.shooting;
  std::optional<StiffnessEstimate> stiffness;
  if (options.switch_when_stiff && shooting.flow.method != Method::BDF) {
    stiffness = stiffness_of_guess(system, shooting.flow, subspace.project(z0), p, period);
    if (stiffness) shooting.flow = after_stiffness(shooting.flow, *stiffness);
  }
  ShootingProblem problem(system, shooting, period);
  problem.record_samples(true);  // for the orbit's describers and a branch's first scales
  const int n = problem.dimension(), m = problem.segments();
  PeriodicOrbit orbit;
  orbit.method = shooting.flow.method;
  orbit.stiffness = stiffness;
  orbit.segments = m;
  orbit.parameters = p;
  orbit.subspace = subspace;
  NewtonSummary& s = orbit.newton;
  const Eigen::VectorXd z = subspace.project(z0);
  const PhaseSection section = problem.section_through(z, p);

  LinearSolveOptions linear;
  linear.prefer_sparse = m > 1;
  linear.rank_tolerance = options.newton.rank_tolerance;

  Eigen::VectorXd x;
  ShootingProblem::Evaluation e;
  try {
    x = project_unknowns(subspace, problem.unknowns_from(z, p, period), n, m);
    e = problem.evaluate(x, p, section, true);
  } catch (const IntegrationError& error) {
    s.outcome = NewtonOutcome::GuessNotIntegrable;
    s.reason = std::string("integration failed at the initial guess: ") + error.what();
    orbit.state0 = z;
    orbit.period = period;
    orbit.flow = problem.statistics();
    orbit.seconds = started.seconds();
    return orbit;
  }
  double norm = inf_norm(e.residual);
  s.residual_norms.push_back(norm);
  const double absolute_tolerance =
      attainable_tolerance(options.newton.residual_tolerance, options.newton.rtol_factor,
                           options.shooting.flow, inf_norm(x.head(n)));
  double tolerance = closure_tolerance(absolute_tolerance, e);
  for (;;) {
    if (norm <= tolerance) {
      s.converged = true;
      s.outcome = NewtonOutcome::Converged;
      s.reason = "residual below tolerance";
      break;
    }
    if (s.iterations >= options.newton.max_iterations) {
      s.outcome = NewtonOutcome::IterationLimit;
      s.reason = "no convergence in " + std::to_string(s.iterations) + " iterations";
      break;
    }
    const auto step = solve_linear(problem.jacobian(e), -e.residual, linear);
    if (!step.x.allFinite()) {
      s.outcome = NewtonOutcome::NonFiniteStep;
      s.reason = "the Newton step is not finite (a Jacobian with non-finite entries?)";
      break;
    }
    s.rank_deficiency = step.rank_deficiency;
    s.sparse = step.sparse;
    ++s.iterations;
    bool accepted = false;
    double alpha = 1.0;
    for (int h = 0; h <= options.newton.max_halvings && !accepted; ++h, alpha *= 0.5) {
      const Eigen::VectorXd trial = project_unknowns(subspace, x + alpha * step.x, n, m);
      try {
        auto et = problem.evaluate(trial, p, section, true);
        const double trial_norm = inf_norm(et.residual);
        if (trial_norm < norm) {
          accepted = true;
          x = trial;
          e = std::move(et);
          norm = trial_norm;
          tolerance = closure_tolerance(absolute_tolerance, e);
          s.halvings += h;
          s.step_norms.push_back(alpha * inf_norm(step.x));
        }
      } catch (const IntegrationError&) {
        // a step too far (e.g. a negative period): halve it
      }
    }
    if (!accepted) {
      // Stalled within ten tolerances: the integration's noise floor, as far as it can go.
      if (norm <= 10 * tolerance) {
        s.converged = true;
        s.outcome = NewtonOutcome::NoiseFloor;
        s.reason = "residual at the integration's noise floor (within 10 tolerances)";
      } else if (norm <= 10 * absolute_tolerance) {
        s.outcome = NewtonOutcome::Vanishing;
        const double amplitude = sampled_amplitude(e.samples);
        std::ostringstream why;
        why.precision(2);
        why << "no orbit: the motion decays to the equilibrium (the residual stalled at " << norm
            << ", " << norm / amplitude << " of an amplitude shrunk to " << amplitude
            << "; an orbit closes to " << kOrbitClosure << " of its amplitude)";
        s.reason = why.str();
      } else {
        s.outcome = NewtonOutcome::NoDescent;
        s.reason = "no step reduced the residual below " + std::to_string(norm);
      }
      break;
    }
    s.residual_norms.push_back(norm);
  }

  orbit.state0 = x.head(n);
  orbit.period = problem.period(x);
  orbit.residual = inf_norm(e.residual.head(n * m));
  const auto jac = problem.jacobian(e);
  orbit.family_dimension = rank_deficiency(jac, options.newton.rank_tolerance);
  orbit.floquet =
      shooting_floquet(problem, e, orbit.state0, orbit.family_dimension, options.floquet, subspace);
  orbit.samples = std::move(e.samples);
  orbit.flow = problem.statistics();
  orbit.seconds = started.seconds();
  return orbit;
}

double closure_tolerance(double absolute, const ShootingProblem::Evaluation& e) {
  return std::min(absolute, kOrbitClosure * sampled_amplitude(e.samples));
}

double sampled_amplitude(const PeriodSamples& samples) {
  if (samples.states.cols() == 0) return std::numeric_limits<double>::infinity();
  const Eigen::VectorXd range =
      samples.states.rowwise().maxCoeff() - samples.states.rowwise().minCoeff();
  return 0.5 * range.maxCoeff();
}

double estimate_period(Flow& flow, const ParameterValues& p, const Eigen::VectorXd& z,
                       double max_period, double dt) {
  const Eigen::VectorXd f = flow.system().rhs(0.0, z, p);
  std::vector<double> times;
  for (double t = dt; t <= max_period; t += dt) times.push_back(t);
  double previous_g = 0.0, previous_t = 0.0, farthest = 0.0, period = 0.0;
  flow.sample_until(z, p, 0.0, times, [&](double t, const Eigen::VectorXd& y) {
    const Eigen::VectorXd d = state_difference(flow.system(), y, z);
    const double g = f.dot(d);
    const double distance = d.cwiseAbs().maxCoeff();
    farthest = std::max(farthest, distance);
    // Back through the section in the flow's direction, near where it started (the orbit
    // crosses the section's plane once more, far away and the other way).
    if (previous_g < 0.0 && g >= 0.0 && distance < 0.2 * farthest) {
      period = previous_t + (t - previous_t) * (-previous_g) / (g - previous_g);
      return true;
    }
    previous_g = g;
    previous_t = t;
    return false;
  });
  return period;
}

namespace {

// A periodically forced system's orbit: its period is the forcing's, so the transient runs over
// whole periods of the forcing (it then ends where the forcing starts again: the state it reaches
// is a guess of the orbit's state at t = 0; none when the transient is under half a period), and
// Newton follows with the period fixed.
PeriodicOrbit find_forced_orbit(const OdeSystem& system, const ParameterValues& p,
                                const Eigen::VectorXd& start, const InvariantSubspace& subspace,
                                const OrbitOptions& options) {
  const Stopwatch started;
  const double period = system.forcing_period(p.data());
  if (!(period > 0.0) || !std::isfinite(period))
    throw std::invalid_argument(
        "find_periodic_orbit: a periodically forced system that declares no forcing period "
        "(OdeSystem::forcing_period); give the period (solve_periodic_orbit)");
  Flow flow(system, options.transient_flow);
  Eigen::VectorXd z = subspace.project(start);
  const long periods = std::lround(options.transient / period);
  try {
    for (long k = 0; k < periods; ++k)
      z = wrap_angles(system, subspace.project(flow.advance(z, p, 0.0, period)));
  } catch (const IntegrationError& e) {
    PeriodicOrbit failed;
    failed.segments = options.shooting.segments;
    failed.parameters = p;
    failed.newton.outcome = NewtonOutcome::TransientFailed;
    failed.newton.reason = std::string("transient integration failed: ") + e.what();
    failed.state0 = z;
    failed.flow = flow.statistics();
    failed.seconds = started.seconds();
    return failed;
  }
  PeriodicOrbit orbit = solve_periodic_orbit(system, p, z, period, subspace, options);
  orbit.flow += flow.statistics();
  orbit.seconds = started.seconds();
  return orbit;
}

}  // namespace

PeriodicOrbit find_periodic_orbit(const OdeSystem& system, const ParameterValues& p,
                                  const Eigen::VectorXd& start, const InvariantSubspace& subspace,
                                  const OrbitOptions& options) {
  const Stopwatch started;
  system.check_parameters(p);
  if (const auto problem = options.validate())
    throw std::invalid_argument("orbit options: " + problem->message());
  if (!system.autonomous()) return find_forced_orbit(system, p, start, subspace, options);
  if (options.use_symmetry)
    if (const auto r = symmetry_reduction(system, p, subspace)) {
      PeriodicOrbit orbit = find_periodic_orbit(
          *r->system, p, r->coordinates.restrict(subspace.project(start)), r->subspace, options);
      orbit = lift(std::move(orbit), *r, subspace, options.floquet);
      orbit.seconds = started.seconds();
      return orbit;
    }
  // Early Newton's rough iterations run in the orbit's subspace in its own coordinates (the
  // restricted system: for the row setup's anti-phase orbit a 2 x 2 monodromy instead of 6 x 6,
  // without the block across that only the multipliers need), where the system has no angles to
  // wrap; the polish, in the whole state, gives all the multipliers. The transient stays in the
  // whole state: restricted, its error norm has no zero components to dilute it, and the
  // anti-phase transient took more steps (87 against 84 million instructions).
  std::unique_ptr<OdeSystem> restricted;
  InvariantSubspace::Coordinates coordinates;
  if (options.use_symmetry && !subspace.is_whole_space() && system.angle_states().empty()) {
    restricted = restrict_system(system, subspace);
    coordinates = subspace.coordinates(system.dimension());
    // A piecewise-smooth system's generic restriction declares no saltation: the whole state.
    if (!carries_sensitivities(*restricted)) restricted.reset();
  }
  Flow flow(system, options.transient_flow);
  Eigen::VectorXd z = subspace.project(start);
  PeriodicOrbit failed;
  failed.segments = options.shooting.segments;
  failed.parameters = p;
  double settled_period = 0.0;  // from a check that found the motion settled
  FlowStatistics tried;         // the work of early Newton attempts not taken
  // An early attempt's first iterations run the shooting's integrator at the transient's
  // tolerance: from where the transient is they only have to approach the orbit, and at the
  // default preset five of them at the shooting's rtol 5e-12 cost as much as the rest of the
  // transient they save (the anti-phase start, 0.18 s either way; with the transient's own BDF
  // and the sensitivity module, too). Newton at the shooting's own settings then starts about
  // the transient's error away and aims a tenth below its tolerance (one or two iterations; at
  // the integration's noise floor it stops within the tolerance as ever).
  OrbitOptions early = options;
  early.shooting.flow.rtol = std::max(options.shooting.flow.rtol, options.transient_flow.rtol);
  early.shooting.flow.atol = std::max(options.shooting.flow.atol, options.transient_flow.atol);
  early.newton.max_iterations = std::min(5, options.newton.max_iterations);
  OrbitOptions polish = options;
  polish.newton.residual_tolerance /= 10.0;
  polish.newton.rtol_factor = std::max(1.0, options.newton.rtol_factor / 10.0);
  OrbitOptions last = options;  // for Newton after the whole transient
  // One stiffness measurement for the whole search (OrbitOptions::switch_when_stiff): at the first
  // period known, at the shooting's own tolerance; every Newton after it runs the method chosen
  // (a measurement per Newton would cost 7 ms each on the row setup at the default).
  std::optional<StiffnessEstimate> stiffness;
  bool chosen = !options.switch_when_stiff || options.shooting.flow.method == Method::BDF;
  auto choose_method = [&](const Eigen::VectorXd& at, double period) {
    if (chosen) return;
    chosen = true;
    stiffness = stiffness_of_guess(system, options.shooting.flow, at, p, period);
    if (!stiffness) return;
    for (OrbitOptions* o : {&early, &polish, &last}) {
      o->shooting.flow = after_stiffness(o->shooting.flow, *stiffness);
      o->switch_when_stiff = false;
    }
  };
  auto measured = [&](PeriodicOrbit orbit) {
    if (stiffness) orbit.stiffness = stiffness;
    return orbit;
  };
  try {
    double next_check = 8.0;
    for (double t = 0.0; t < options.transient;) {
      const double dt = std::min(1.0, options.transient - t);
      z = wrap_angles(system, subspace.project(flow.advance(z, p, 0.0, dt)));
      t += dt;
      if (options.settle_tolerance > 0.0 && t >= next_check && t < options.transient) {
        // Settled when one period later the motion is back within the tolerance, relative to
        // the state's size (Newton's first residual is about that): checked at 8, 12, 18, 27 and
        // 40.5 s, two periods of extra integration each, against most of the transient saved.
        next_check *= 1.5;
        const double period =
            estimate_period(flow, p, z, options.max_period, options.max_period / 1e4);
        if (period > 0.0) {
          const Return back = one_return(flow, p, z, period, subspace);
          const double size = std::min(state_size(z), back.size), moved = back.moved;
          if (moved <= options.settle_tolerance * size) {
            settled_period = period;
            break;
          }
          if (moved <= options.early_newton_below * size) {
            choose_method(z, period);
            // In V the linear solver is chosen for the restricted system (a structured one
            // asked of the whole may have no structure there).
            OrbitOptions early_in_v = early;
            early_in_v.shooting.flow.linear_solver = LinearSolver::Automatic;
            const PeriodicOrbit rough =
                restricted ? solve_periodic_orbit(*restricted, p, coordinates.restrict(z), period,
                                                  InvariantSubspace(), early_in_v)
                           : solve_periodic_orbit(system, p, z, period, subspace, early);
            tried += rough.flow;
            if (rough.converged()) {
              const Eigen::VectorXd guess =
                  restricted ? coordinates.embed(rough.state0) : rough.state0;
              PeriodicOrbit orbit =
                  solve_periodic_orbit(system, p, guess, rough.period, subspace, polish);
              if (approached(system, orbit, z, options.floquet)) {
                orbit.flow += flow.statistics();
                orbit.flow += tried;
                orbit.seconds = started.seconds();
                return measured(std::move(orbit));
              }
              tried += orbit.flow;
            }
          }
        }
      }
    }
  } catch (const IntegrationError& e) {
    failed.newton.outcome = NewtonOutcome::TransientFailed;
    failed.newton.reason = std::string("transient integration failed: ") + e.what();
    failed.state0 = z;
    return failed;
  }
  const double period = settled_period > 0.0 ? settled_period
                                             : estimate_period(flow, p, z, options.max_period,
                                                               options.max_period / 1e4);
  if (!(period > 0.0)) {
    failed.newton.outcome = NewtonOutcome::NoPeriod;
    failed.newton.reason = "no return to the section within " + format_double(options.max_period) +
                           " s after the transient (an equilibrium, or a longer period? "
                           "max_period, --max-period, raises the limit)";
    failed.state0 = z;
    failed.flow = flow.statistics();
    failed.seconds = started.seconds();
    return failed;
  }
  choose_method(z, period);
  PeriodicOrbit orbit = measured(solve_periodic_orbit(system, p, z, period, subspace, last));
  if (!orbit.converged()) {
    // Say whether the transient had settled: how far the motion came back in one period, against
    // its amplitude, and whether the next return came closer (a motion that grows, as the row
    // setup without hinge damping, whose swings go over the top, moves by a small part of its
    // growing range but never settles).
    try {
      const Return first = one_return(flow, p, z, period, subspace);
      const Return next = one_return(flow, p, first.later, period, subspace);
      const double size = std::min(state_size(z), std::max(first.size, next.size));
      const double moved = next.moved;
      const bool settled = moved <= 1e-3 * size && moved <= first.moved;
      std::ostringstream note;
      note.precision(2);
      note << "; after the " << options.transient << " s transient the motion still moved by "
           << moved << " (" << 100.0 * moved / size << "% of its size) in one period, "
           << first.moved << " in the one before: "
           << (settled ? "it had settled, so the orbit may be hard for Newton here"
                       : "it had not settled on a periodic orbit (a longer transient, or there "
                         "may be none, e.g. when no dissipation balances a drive)");
      orbit.newton.reason += note.str();
    } catch (const IntegrationError&) {
    }
  }
  orbit.flow += flow.statistics();
  orbit.flow += tried;
  orbit.seconds = started.seconds();
  return orbit;
}

}  // namespace sympathy
