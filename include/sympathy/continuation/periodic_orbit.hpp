// Periodic orbits: Newton on the shooting problem, and finding an orbit from a start.
//
// Newton: full steps when they reduce the residual, halved otherwise; on a continuum of orbits
// (a rank-deficient Jacobian) the minimum-norm step, and the continuum's dimension is reported.
// Converged when |residual|_inf <= residual_tolerance. Every orbit carries its Newton residual,
// its Floquet multipliers and the distance of its trivial multiplier from 1.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/shooting.hpp"
#include "sympathy/core/invariant_subspace.hpp"
#include "sympathy/core/stiffness.hpp"
#include "sympathy/floquet/floquet.hpp"

namespace sympathy {

struct NewtonOptions {
  // On |Phi_T(z0) - z0|_inf and the phase condition; never below `rtol_factor` times the
  // integration's rtol, which is as far as the residual of an integration can go (the bench
  // measures residuals of 5-20 rtol at the noise floor).
  double residual_tolerance = 1e-9;
  double rtol_factor = 20.0;
  int max_iterations = 20;
  int max_halvings = 8;
  double rank_tolerance = 1e-6;  // see LinearSolveOptions

  OptionCheck validate() const;
};

// The residual tolerance an integration at `flow` settings can meet: the integration's error is
// relative, so the noise floor of |Phi_T(z0) - z0|_inf grows with the state's size
// (`state_size`, its largest |z_i|): rtol_factor * rtol * max(1, state_size). An absolute floor
// refused converged orbits whose states are of order 100 (residual 1.1e-8 at rtol 5e-12).
inline double attainable_tolerance(double tolerance, double rtol_factor, const FlowOptions& flow,
                                   double state_size = 1.0) {
  return std::max(tolerance, rtol_factor * flow.rtol * std::max(1.0, state_size));
}

// How a search for an orbit ended, for programs to switch on (the summary's reason says it for
// people, with numbers).
enum class NewtonOutcome {
  Converged,           // the residual fell below the tolerance
  NoiseFloor,          // stalled within 10 tolerances: as far as the integration's noise allows
  NotRun,              // nothing tried yet
  IterationLimit,      // max_iterations reached
  NoDescent,           // no halving of the step lowered the residual
  NonFiniteStep,       // the Newton step was not finite
  GuessNotIntegrable,  // the integration failed at the initial guess
  TransientFailed,     // the transient integration before Newton failed
  NoPeriod,            // no return to the section after the transient
  Vanishing,           // the residual stalled above kOrbitClosure of a shrinking amplitude:
                       // no orbit, the motion decays to an equilibrium
};

// An orbit is one only where it closes to within this fraction of its amplitude about its mean
// (max over states of half the range over the period), besides the absolute tolerance: on the
// Hopf normal form at mu = 0 (no cycle, r' = -r^3) Newton shrank the "orbit" to amplitude 6.7e-4
// and stalled at the absolute noise floor, 1.5e-9, which is its per-period decay r^3 T: 2.2e-6 of
// its amplitude (issue 32: reported converged and stable). A genuine orbit converges
// quadratically through this: at mu = 1e-4 (amplitude 0.01) it asks for 1e-9, the default
// tolerance.
constexpr double kOrbitClosure = 1e-7;

// Half the largest range of a state over the sampled period (inf of the samples' amplitude about
// their mean); infinity without samples.
double sampled_amplitude(const PeriodSamples& samples);
// The residual an orbit must close to: `absolute`, and kOrbitClosure of the amplitude of the
// period `e` sampled (none sampled: `absolute` alone). One rule for Newton on an orbit
// (find_periodic_orbit) and a continuation's corrector.
double closure_tolerance(double absolute, const ShootingProblem::Evaluation& e);
std::string to_string(NewtonOutcome o);

struct NewtonSummary {
  bool converged = false;  // Converged or NoiseFloor
  NewtonOutcome outcome = NewtonOutcome::NotRun;
  std::string reason;  // why it stopped
  int iterations = 0;
  std::vector<double> residual_norms;  // |r|_inf at each iterate, the start included
  std::vector<double> step_norms;      // |dx|_inf of each accepted step
  int halvings = 0;
  int rank_deficiency = 0;  // at the last Jacobian: the dimension of a continuum
  bool sparse = false;      // steps solved by the sparse LU (UMFPACK)
};

// The defaults of an orbit computation, each set here and nowhere else: the shooting flow at rtol
// 1e-11, atol 1e-13 (the trivial multiplier's error is about 200-500 rtol, measured on the row
// setup: within 1e-8 of 1 at this setting), the transient at rtol 1e-8, atol 1e-10 (it only has
// to approach the orbit).
struct OrbitOptions {
  ShootingOptions shooting;
  NewtonOptions newton;
  FloquetOptions floquet;
  double transient = 60.0;  // s of integration before Newton (find_periodic_orbit) ...
  // ... cut short where the motion has settled: back within this one period later, relative to
  // the smaller of the state's size and the motion's own amplitude (the largest half range of a
  // state over the period: an orbit about an equilibrium far from the origin is dwarfed by the
  // state), checked at 8 s
  // and then every half again as long (12, 18, 27, 40.5 s); 0: always the whole transient (and no
  // early Newton below). At 1e-4 Newton starts about that far from the orbit and needs two or three
  // iterations (row setup: the in-phase orbit at Table III settles by 24 s, the anti-phase start
  // needs most of the 60 s).
  double settle_tolerance = 1e-4;
  // ... or where it moved by less than this at a check, Newton is tried there (at most five
  // iterations) and its orbit taken if it converged within a tenth of the state's size of where
  // the transient was and is stable in the space the transient runs in (every multiplier but the
  // trivial, structural and symmetry-breaking ones inside the unit circle by the stability
  // tolerance): an orbit the transient was approaching. Otherwise the transient goes on. The
  // anti-phase orbit (row setup, Table II, k = 1) is approached at 0.92 a period, so the motion
  // moves by 1.4e-3 at 12 s and by 1e-4 only after 32 s; Newton from 12 s converges in four
  // iterations, and the start costs 0.04 s instead of 0.07 s (fast preset; default 0.09 s
  // instead of 0.17 s; `orbit --start anti-phase --set k=1`, 2026-11-24). 0: never.
  double early_newton_below = 2e-3;
  double max_period = 10.0;    // s: the longest period looked for
  FlowOptions transient_flow;  // for the transient and the period estimate
  // Orbits of interchangeable units that move alike are computed in their smallest block
  // (symmetry_reduction.hpp); false: in the whole state (for comparison).
  bool use_symmetry = true;
  // Where the shooting flow's method is a non-stiff one (Adams, ERK): measure the stiffness
  // indicator (core/stiffness.hpp) over the guess's period at the shooting's own tolerance before
  // Newton, and run BDF with Newton instead where it is above kStiffIndicator. A continuation
  // measures once, at its start orbit. false: the method as set.
  bool switch_when_stiff = false;
  // The default accuracy preset (accuracy.hpp): Adams at rtol 5e-12 with the switch above on,
  // the transient BDF at 1e-8.
  OrbitOptions();

  OptionCheck validate() const;
};

struct PeriodicOrbit {
  Eigen::VectorXd state0;  // a point of the orbit (on the phase section)
  double period = 0.0;
  ParameterValues parameters;  // the system's parameter values the orbit belongs to
  // The subspace a symmetry keeps that the orbit lies in (the whole space if none was declared):
  // its multipliers are labelled by it (SymmetryKind), and a branch from it keeps it.
  InvariantSubspace subspace;
  FloquetAnalysis floquet;
  double residual = 0.0;  // |Phi_T(z0) - z0|_inf at the converged point
  int segments = 1;
  // The largest growth of a perturbation over one shooting segment, max_k |D^-1 M_k D|_inf with
  // M_k the segment's transition matrix and D the state's scales (a continuation point's; 0 where
  // not measured): what one segment must resolve. The corrector's noise floor is about rtol / 500
  // times it (AUTO's fhn and ab): Newton stalls above about 1e5 at rtol 5e-12 (fhn's canard, 5e5
  // to 2e6 on one segment), the measure a segment criterion is to act on.
  double segment_growth = 0.0;
  // The same of the monodromy, |D^-1 M D|_inf: the multipliers' noise floor is about rtol times it
  // (what events located on the tangent and user points are trusted against; see
  // `trust_limit_for`).
  double monodromy_growth = 0.0;
  int family_dimension = 0;  // > 0: the orbit belongs to a continuum of orbits
  NewtonSummary newton;
  FlowStatistics flow;  // integration work of the whole computation
  double seconds = 0.0;
  std::string reduction;  // how a symmetry reduced the computation; empty: the whole state
  // The shooting's integrator (BDF where OrbitOptions::switch_when_stiff switched to it), and
  // the stiffness measured where that option asked for it.
  Method method = Method::BDF;
  std::optional<StiffnessEstimate> stiffness;
  // The period sampled by the run that confirmed the orbit (empty where none was kept; checked
  // against state0 and period before use: PeriodSamples::of).
  PeriodSamples samples;
  bool converged() const { return newton.converged; }
};

// The multipliers of the orbit at the shooting unknowns' first state z0, from an evaluation with
// derivatives there (at its parameter values): f at z0 (if autonomous) and the `family_dimension`
// directions of a continuum (null vectors of the shooting Jacobian) are what the analysis sets
// apart.
// With a `subspace` (not the whole space) the multipliers are labelled by it (label_symmetry).
FloquetAnalysis shooting_floquet(const ShootingProblem& problem,
                                 const ShootingProblem::Evaluation& e, const Eigen::VectorXd& z0,
                                 int family_dimension, const FloquetOptions& options,
                                 const InvariantSubspace& subspace = {});

// Newton from a guess (z0, T) at parameter values p. Keeps every iterate in `subspace`.
PeriodicOrbit solve_periodic_orbit(const OdeSystem& system, const ParameterValues& p,
                                   const Eigen::VectorXd& z0, double period,
                                   const InvariantSubspace& subspace, const OrbitOptions& options);

// From a start: a transient integration inside `subspace` (projected after every second, so
// that even orbits unstable in the full space are approached), the period from the first return
// to the section through the end point, then Newton. A periodically forced system's period is
// the forcing's (OdeSystem::forcing_period; std::invalid_argument where it declares none): its
// transient runs over the nearest whole number of forcing periods (none under half a period),
// then Newton with the period fixed.
PeriodicOrbit find_periodic_orbit(const OdeSystem& system, const ParameterValues& p,
                                  const Eigen::VectorXd& start, const InvariantSubspace& subspace,
                                  const OrbitOptions& options);

// Period of the orbit through z: the first return to the section through z across the flow,
// found by sampling every `dt` up to `max_period`; 0 if there is none.
double estimate_period(Flow& flow, const ParameterValues& p, const Eigen::VectorXd& z,
                       double max_period, double dt);

}  // namespace sympathy
