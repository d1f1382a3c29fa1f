// The flow of an OdeSystem, computed by SUNDIALS (CVODES, or ARKODE's explicit Runge-Kutta
// stepper), with or without sensitivities.
//
// One Flow owns one integrator and every SUNDIALS object it needs (context, vectors, matrix,
// linear and nonlinear solvers) and reuses them across calls: a continuation makes thousands of
// calls. Each call asks only for what it needs: `advance` integrates the state alone;
// `advance_with_sensitivities` adds the n state columns (the transition matrix) and/or the
// columns of named parameters. The parameter values travel with each call (ParameterValues): a
// flow holds those of the call it is computing and nothing after.
//
// Three integrators sit behind the same calls (FlowOptions::method and ::sensitivities; the step
// loop below runs unchanged on each, core/flow_stepper.hpp):
//   - CVODES with its forward-sensitivity module (the default; BDF or Adams): the state and each
//     sensitivity column in vectors of their own, the columns in the error test;
//   - CVODE on the augmented system: the state with its variational equations appended, one
//     vector of n (1 + columns) entries, one error test over all of it;
//   - ARKODE's ERKStep (method ERK) on the same augmented system: Dormand-Prince 5(4) or
//     Verner 6(5).
// Measured on the row setup (n = 6; bench section (f), cases/cli/common.cpp): one period of the
// anti-phase orbit with the monodromy and a parameter column at rtol 1e-11 takes ~3,000 BDF steps
// with the forward module at 10-15 us a step (per-vector overhead on seven short vectors), 1,256
// Adams steps on the augmented system and 943 Dormand-Prince steps; the anti-phase k-branch
// (k = 1 to 100 N/m, located points within 5e-10 to 8e-10 of the reference) took 3.8 s with the
// forward module (BDF, 1e-11), 2.0 s augmented (Adams, fixed point, 5e-12) and 1.2 s with
// Dormand-Prince (1e-10). Dormand-Prince is explicit: a stiff system (a stiff platform, large k
// and c) forces small steps on it, where BDF is safe. Leaving the sensitivities out of the error
// test was measured slower and 16x less accurate (NUMERICS.md): all three keep them in.
//
// Steep zones (OdeSystem::steep_zones) are resolved explicitly: on geometric levels
// v_0 = scale > v_1 = v_0/3 > ... down to below the zone's width, while |z_c| <= v_l the step
// is capped at fraction * v_(l+1) / |dz_c/dt|, so no step can jump over the next inner level,
// and the innermost band (the steep part itself) is crossed in several steps. With the explicit
// Runge-Kutta method a component on its way out is capped by the level ahead of it, its band's
// outer one (v_l): 8% fewer steps on the anti-phase k-branch's fast preset; one that turns back
// is capped by the inner level again from the step after it turned. (CVODE's multistep methods
// keep the inner level both ways: with the outer one Adams took 1.7% more steps.) Error control
// alone steps straight over such features (see NUMERICS.md; an explicit Runge-Kutta method
// without the caps keeps an error of 1.9e-6 in the multipliers whatever its tolerance). The
// integrator takes one internal step at a time and reads the bands off the state after each; a
// step that crosses a level was capped by the band it started in, and lands in the next. CVODES
// and ARKODE apply a new maximum step only when they next choose a step size, so a stop time one
// capped step ahead also shortens the step already planned. (Root functions on the levels were
// tried first: CVODES returns the same root forever when two identical ones, from symmetric
// pendula, coincide.) On the augmented vector the state is its first n components, so the zones
// and caps carry over unchanged.
//
// Switching surfaces (OdeSystem::switching_functions) are located by the integrator's root
// finding, and the integration restarts at each, so that no step straddles a jump of f. For a
// HybridSystem each crossing also applies the surface's reset and maps the sensitivity columns by
// the saltation matrix (core/saltation.hpp): its transition matrices and parameter sensitivities
// are those of the hybrid flow (tests/core/hybrid_flow_test.cpp: a relay's transition across a
// turning point within 1e-10 of its closed form at rtol 1e-12). Other systems with surfaces are
// integrated, but refuse sensitivities.
#pragma once

#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/hybrid_system.hpp"
#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy {

namespace detail {  // core/flow_stepper.hpp
struct FlowCall;
class FlowStepper;
}  // namespace detail

// CVODES's linear multistep methods (BDF, Adams), or ARKODE's explicit embedded Runge-Kutta
// pairs (ERK; its table in FlowOptions::explicit_table). ERK needs sensitivities = Augmented and
// ignores the nonlinear and linear solver and the corrector.
enum class Method { BDF, Adams, ERK };
// ERK tables: Dormand-Prince 5(4), 7 stages (ARKODE_DORMAND_PRINCE_7_4_5), or Verner 6(5), 8
// stages (ARKODE_VERNER_8_5_6). Debian's ARKODE 6.4.1 gets far less from Verner than from
// Dormand-Prince at equal rtol, in more steps: a plain ERKStep run of a harmonic oscillator at
// rtol 1e-10 (no Flow involved) took 676 steps to an error of 3.3e-8 against Dormand-Prince's 278
// steps and 1.4e-11, though the table passes ARKODE's own order check (6 and 5); on the anti-phase
// k-branch Verner at 1e-9 located the events to 2e-7 in 2.8 s, Dormand-Prince to 2.7e-10 in 1.1 s.
// Kept as an option for comparison; Dormand-Prince is the default.
enum class ExplicitTable { DormandPrince, Verner };
// How sensitivities are integrated: CVODES's forward-sensitivity module (each column its own
// vector, the staggered or simultaneous corrector), or the variational equations appended to the
// state as one augmented system (CVODE's BDF or Adams, or ERK). Both need the system's own
// derivatives for parameter columns; the augmented system for state columns too.
enum class Sensitivities { ForwardModule, Augmented };
enum class NonlinearSolver { Newton, FixedPoint };
// The linear solver of the BDF Newton iteration, for (I - gamma J) x = b. Dense: LAPACK-style LU
// of the full matrix. KLU: sparse LU on the system's jacobian_pattern(). Structured: for
// systems whose Jacobian is sparse plus low rank (OdeSystem::low_rank_jacobian): KLU on
// I - gamma S and the Woodbury identity for the rank-r rest, O(nnz + n r) a solve instead of
// O(n^2), a factorization one sparse LU and r solves instead of O(n^3). CVODES decides when to
// evaluate the Jacobian and factor, as for the other two. Automatic: structured where the system
// offers that form and its sparse part is large against the rank (n > 2 (r + 3): for metronomes,
// more than three of them, where bench section (e) measured it faster), dense otherwise.
enum class LinearSolver { Automatic, Dense, KLU, Structured };
enum class SensitivityCorrector { Staggered, Simultaneous };
// Where the Jacobian and the sensitivity right-hand side come from: the system's own
// derivatives, or CVODES's difference quotients (state sensitivities only; for comparison).
enum class Derivatives { Model, DifferenceQuotients };

struct FlowOptions {
  double rtol = 1e-10;
  double atol = 1e-12;
  Method method = Method::BDF;
  Sensitivities sensitivities = Sensitivities::ForwardModule;
  ExplicitTable explicit_table = ExplicitTable::DormandPrince;  // method ERK only
  NonlinearSolver nonlinear_solver = NonlinearSolver::Newton;
  LinearSolver linear_solver = LinearSolver::Automatic;
  SensitivityCorrector corrector = SensitivityCorrector::Staggered;
  Derivatives derivatives = Derivatives::Model;
  // Per call, and per output interval where a call samples its solution (a simulation of
  // 2000 s, about 1000 steps a second on the row setup, stopped at t = 1017 with a limit per run).
  long max_steps = 1000000;
  double max_step = 0.0;  // 0: no limit
  bool resolve_steep_zones = true;
  double steep_step_fraction =
      0.5;  // below 2/3, so that no step jumps a level (see update_max_step)

  OptionCheck validate() const;
};

// The linear solver a flow of `system` with `options` uses: Automatic resolved (dense with
// difference quotients, which the structured solver cannot use), the others as asked.
LinearSolver resolved_linear_solver(const OdeSystem& system, const FlowOptions& options);

std::string to_string(Method m);
std::string to_string(LinearSolver s);
std::string to_string(Sensitivities s);
std::string to_string(ExplicitTable t);

struct FlowStatistics {
  long calls = 0;
  long steps = 0;
  long rhs_evaluations = 0;
  long jacobian_evaluations = 0;
  long variational_evaluations = 0;  // calls of the sensitivity right-hand side
  long linear_setups = 0;            // factorizations of I - gamma J
  long error_test_failures = 0;
  long nonlinear_iterations = 0;
  long steep_roots = 0;  // level crossings of steep zones (band changes)
  long switchings = 0;   // restarts at switching surfaces
  FlowStatistics& operator+=(const FlowStatistics& other);
};

struct FlowDerivatives {
  Eigen::VectorXd state;                    // z(t1)
  Eigen::MatrixXd transition;               // dz(t1)/dz(t0), n x n (empty if not asked)
  Eigen::MatrixXd parameter_sensitivities;  // dz(t1)/dp, one column per asked parameter
};

class Flow {
 public:
  explicit Flow(const OdeSystem& system, FlowOptions options = {});
  ~Flow();
  Flow(const Flow&) = delete;
  Flow& operator=(const Flow&) = delete;

  // z(t1) from z(t0) = z0 at parameter values p. No sensitivities.
  Eigen::VectorXd advance(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                          double t1);

  // Integrates from z0 at t0 to t1 (no sensitivities) and calls `observer(t_old, t_new, z)` after
  // each of the integrator's internal steps, with the step's ends and the state where it ended:
  // the steps themselves, for measurements of the run (core/stiffness.hpp). Returns z(t1).
  Eigen::VectorXd advance_observing_steps(
      const Eigen::VectorXd& z0, const ParameterValues& p, double t0, double t1,
      const std::function<void(double, double, const Eigen::VectorXd&)>& observer);

  // Integrates from z0 at t0 and calls `observer(t, z)` at each of `times` (increasing, >= t0).
  void sample(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
              std::span<const double> times,
              const std::function<void(double, const Eigen::VectorXd&)>& observer);
  // The same, stopping as soon as `done(t, z)` returns true; returns whether it did.
  bool sample_until(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                    std::span<const double> times,
                    const std::function<bool(double, const Eigen::VectorXd&)>& done);

  // z(t1) and its derivatives: the transition matrix if `state` is true, and dz(t1)/dp for each
  // of `parameters` (indices into the system's parameters).
  FlowDerivatives advance_with_sensitivities(const Eigen::VectorXd& z0, const ParameterValues& p,
                                             double t0, double t1, bool state = true,
                                             std::span<const int> parameters = {});
  // The same, calling `observer(t, z)` on the way with the state at each of `times` (increasing,
  // in [t0, t1]) from the step's interpolant: the trajectory of a run that is made anyway (the
  // end state and derivatives are those of the call without it).
  FlowDerivatives advance_with_sensitivities(
      const Eigen::VectorXd& z0, const ParameterValues& p, double t0, double t1, bool state,
      std::span<const int> parameters, std::span<const double> times,
      const std::function<void(double, const Eigen::VectorXd&)>& observer);

  // Integrates once from z0 at t0 and calls `observer(t, z, S)` at each of `times` (increasing,
  // >= t0), where S (n x columns) holds dz(t)/dz0[c] for each of `initial_components`, then
  // dz(t)/dp for each of `parameters`; both interpolated in the step, under error control.
  void sample_with_sensitivities(
      const Eigen::VectorXd& z0, const ParameterValues& p, double t0, std::span<const double> times,
      std::span<const int> initial_components, std::span<const int> parameters,
      const std::function<void(double, const Eigen::VectorXd&, const Eigen::MatrixXd&)>& observer);

  const FlowOptions& options() const { return options_; }
  const OdeSystem& system() const { return system_; }
  const FlowStatistics& statistics() const { return statistics_; }
  // A hybrid system's crossings since the last call began: how often each switching surface was
  // crossed (events only; empty for a smooth system). A periodic orbit's, over one period, say
  // which surfaces it crosses how often: where that changes along a branch, an orbit grazed a
  // surface between two points.
  const std::vector<int>& crossings() const { return crossings_; }
  // Where the last call of a hybrid system began on a switching surface that the fields on both
  // sides push away from (two solutions start there): which one it followed; empty otherwise.
  const std::string& two_solutions() const { return two_solutions_; }
  void reset_statistics() { statistics_ = FlowStatistics{}; }

 private:
  // Sensitivity columns: one per initial component (seeded with its unit vector), then one per
  // parameter (seeded with zero).
  void start(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
             std::span<const int> initial_components, std::span<const int> parameters);
  // Integrates to t_end one internal step at a time; see flow.cpp.
  void integrate_to(double t_end, const std::function<bool(double, double)>& after_step = {});
  void step_to(double t_end, const std::function<bool(double, double)>& after_step);
  // The sampling behind sample_until and sample_with_sensitivities: `observer(t, z, S)` at each
  // of `times` (S with no columns when there are no sensitivities); true from it stops the run.
  bool sample_run(
      const Eigen::VectorXd& z0, const ParameterValues& p, double t0, std::span<const double> times,
      std::span<const int> initial_components, std::span<const int> parameters,
      const std::function<bool(double, const Eigen::VectorXd&, const Eigen::MatrixXd&)>& observer);
  void configure_zones();
  int band_of(std::size_t zone, double value) const;
  void update_bands(double t);
  void on_switching();
  void start_sides(const Eigen::VectorXd& z0);
  void cross_surfaces_here();
  std::optional<double> hidden_excursion(double t_old);
  void check_chattering(int surface);
  void update_max_step(double t);
  bool outward_caps_looser(int band, int innermost) const;
  void collect_statistics();

  const OdeSystem& system_;
  std::vector<int> crossings_;  // per switching surface, since the call began
  std::string two_solutions_;   // see two_solutions()
  // Per switching surface: its last crossing, the interval before it and how many intervals in a
  // row shrank geometrically (check_chattering).
  struct CrossingTimes {
    double last = std::numeric_limits<double>::quiet_NaN();
    double interval = std::numeric_limits<double>::quiet_NaN();
    int shrinking = 0;
  };
  std::vector<CrossingTimes> crossing_times_;
  // The start of the last step taken again for a hidden excursion (hidden_excursion), and the
  // last step's end as it saw it (the next step's start).
  double redone_from_ = std::numeric_limits<double>::quiet_NaN();
  struct StepEnd {
    double t = std::numeric_limits<double>::quiet_NaN();
    Eigen::VectorXd z, f;   // the state and the region's field
    std::vector<double> g;  // the switching functions
  };
  StepEnd step_end_;
  FlowOptions options_;
  FlowStatistics statistics_;
  std::unique_ptr<detail::FlowCall> call_;        // the call now being integrated
  std::unique_ptr<detail::FlowStepper> stepper_;  // the integrator
  long steps_since_output_ = 0;  // steps since the call began or last gave a sample

  // Steep zones with their levels.
  std::vector<SteepZone> zones_;
  std::vector<std::vector<double>> levels_;  // per zone, decreasing
  std::vector<int> bands_;                   // per zone: innermost level l with |z_c| <= v_l
  std::vector<double> last_abs_;             // per zone: |z_c| after the last step
  std::vector<char> approaching_;            // per zone: |z_c| fell in the last step
  std::vector<double> dz_scratch_;

  std::optional<double> forced_stop_;  // a stop time that shortens the step already planned
  Eigen::MatrixXd seeds_;              // initial sensitivity columns of the call
  double t_ = 0.0;
};

// The most output samples a run takes (Flow::sample's `times`): a bound chosen, not hit. 1e7
// samples are 80 MB of times and a CSV of about a gigabyte (issue 32: --dt 1e-300 ended in
// "vector::reserve", --dt 1e-8 --t-end 60 in bad_alloc).
constexpr double kMaxSamples = 1e7;

// 0, dt, 2 dt, ... up to t_end, and t_end itself where dt does not divide it (to 1e-12): the
// sample times of a run. Expects 0 < dt <= t_end and t_end / dt <= kMaxSamples (the callers check
// and name their options).
std::vector<double> sample_times(double t_end, double dt);

}  // namespace sympathy
