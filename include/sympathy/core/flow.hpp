// The flow of an OdeSystem, computed by CVODES, with or without forward sensitivities.
//
// One Flow owns one CVODES integrator and every SUNDIALS object it needs (context, vectors,
// matrix, linear and nonlinear solvers) and reuses them across calls: a continuation makes
// thousands of calls. Each call asks only for what it needs: `advance` integrates the state
// alone; `advance_with_sensitivities` adds the n state columns (the transition matrix) and/or
// the columns of named parameters. The parameter values travel with each call (ParameterValues):
// a flow holds those of the call it is computing and nothing after.
//
// Steep zones (OdeSystem::steep_zones) are resolved explicitly: on geometric levels
// v_0 = scale > v_1 = v_0/3 > ... down to below the zone's width, while |z_c| <= v_l the step
// is capped at fraction * v_(l+1) / |dz_c/dt|, so no step can jump over the next inner level,
// and the innermost band (the steep part itself) is crossed in several steps. Error control
// alone steps straight over such features (see NUMERICS.md). The integrator takes one internal
// step at a time and reads the bands off the state after each; a step that crosses a level was
// capped by the band it started in, and lands in the next. CVODES applies a new maximum step
// only when it next changes the step size, so a stop time one capped step ahead also shortens
// the step it has already planned. (Root functions on the levels were tried first: CVODES
// returns the same root forever when two identical ones, from symmetric pendula, coincide.)
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy {

enum class Method { BDF, Adams };
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
  NonlinearSolver nonlinear_solver = NonlinearSolver::Newton;
  LinearSolver linear_solver = LinearSolver::Automatic;
  SensitivityCorrector corrector = SensitivityCorrector::Staggered;
  Derivatives derivatives = Derivatives::Model;
  long max_steps = 1000000;  // per call
  double max_step = 0.0;     // 0: no limit
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

// Raised when CVODES fails (step size underflow, too many steps, a failing right-hand side).
class IntegrationError : public std::runtime_error {
 public:
  IntegrationError(const std::string& what, double t) : std::runtime_error(what), t_(t) {}
  double time() const { return t_; }

 private:
  double t_;
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
  void reset_statistics() { statistics_ = FlowStatistics{}; }

 private:
  struct Cvodes;  // the SUNDIALS objects, owned
  friend struct FlowCallbacks;

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
  void configure_roots();
  int band_of(std::size_t zone, double value) const;
  void update_bands(double t);
  void on_switching();
  void update_max_step(double t);
  void collect_statistics();
  [[noreturn]] void fail(int flag, const char* function);

  const OdeSystem& system_;
  FlowOptions options_;
  FlowStatistics statistics_;
  std::unique_ptr<Cvodes> cv_;

  // Steep zones with their levels, and the system's switching functions (CVODES roots).
  std::vector<SteepZone> zones_;
  std::vector<std::vector<double>> levels_;  // per zone, decreasing
  std::vector<int> bands_;                   // per zone: innermost level l with |z_c| <= v_l
  int switching_count_ = 0;
  std::vector<int> root_info_;
  std::vector<double> dz_scratch_;

  std::optional<double> forced_stop_;  // a stop time that shortens the step CVODES planned
  ParameterValues values_;             // parameter values of the call now being integrated
  std::vector<int> parameters_;        // parameters of the sensitivity columns now being integrated
  double t_ = 0.0;
  std::string last_error_;
  std::exception_ptr callback_error_;
};

}  // namespace sympathy
