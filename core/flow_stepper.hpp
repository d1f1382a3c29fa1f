// The integrator behind a Flow, one internal step at a time (private to core).
//
// Flow's own logic (steep-zone bands and step caps, the stop time that shortens a step already
// planned, restarts at switching surfaces, outputs interpolated inside a step) talks to this
// interface only; three SUNDIALS integrators implement it:
//   - CVODES with its forward-sensitivity module (flow_cvodes.cpp): the state in one N_Vector,
//     one N_Vector per sensitivity column; BDF or Adams;
//   - CVODE on the augmented system (flow_augmented.cpp): the state and its variational columns
//     as one N_Vector [z; S_0; ...; S_(c-1)]; Adams with fixed-point iteration, or BDF with Newton;
//   - ARKODE's ERKStep on the same augmented system (flow_erk.cpp): an explicit embedded
//     Runge-Kutta pair (Dormand-Prince 5(4) or Verner 6(5)).
// On the augmented vector the state is its first n components, so the steep zones (components of
// the state) and their caps carry over unchanged.
#pragma once

#include <cmath>
#include <exception>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/flow.hpp"
#include "sympathy/core/hybrid_system.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy::detail {

// What the callbacks evaluate: the system at the parameter values of the call now being
// integrated, with its sensitivity columns. The Flow owns it and sets it at each call's start;
// its stepper reads it.
struct FlowCall {
  explicit FlowCall(const OdeSystem& s)
      : system(s),
        // A HybridSystem without surfaces (a model whose smooth forms have none) is a smooth one.
        hybrid(s.switching_count() > 0 ? dynamic_cast<const HybridSystem*>(&s) : nullptr) {}
  const OdeSystem& system;
  // The system as a piecewise-smooth one with surfaces, where it is: its flow integrates each
  // region's field, and its crossings map the sensitivity columns by their saltation matrices
  // and apply its resets (Flow).
  const HybridSystem* hybrid;
  ParameterValues values;
  // A hybrid system's region the flow is in (a sign per switching function, set by the Flow at
  // the start and at each crossing): the integrator sees that region's field, extended beyond its
  // surfaces, so that no step straddles a discontinuity (hybrid_system.hpp).
  std::vector<int> sides;
  // Sensitivity columns: the first state_columns seeded with unit vectors, then one per entry of
  // `parameters` (seeded with zero).
  int columns = 0;
  std::vector<int> parameters;
  // Per switching function, the crossings that are events (HybridSystem::crossing_direction: +1,
  // -1, 0); empty: every crossing.
  std::vector<int> root_directions;
  // A C++ exception from a callback: stored, the C code told to stop, rethrown after it returns.
  std::exception_ptr callback_error;
  std::string last_error;  // SUNDIALS's last error message
  // The first non-finite right-hand side of the step under way, described (t, the derivative,
  // the state and parameters); cleared at each step. The integrator retries smaller steps; when
  // it gives up, the failure says this rather than only a return code.
  std::string nonfinite;

  // The field and its derivatives as the integrator sees them: the region's (sides) for a hybrid
  // system, else the system's; at the call's parameter values, for its sensitivity columns.
  void rhs(double t, const double* z, double* dz) const {
    if (hybrid)
      hybrid->rhs_on_sides(t, z, values.data(), sides.data(), dz);
    else
      system.rhs(t, z, values.data(), dz);
  }
  void jacobian(double t, const double* z, Eigen::MatrixXd& jac) const {
    if (hybrid)
      hybrid->jacobian_on_sides(t, z, values.data(), sides.data(), jac);
    else
      system.jacobian(t, z, values.data(), jac);
  }
  void variational_rhs(double t, const double* z, int count, const double* const* S,
                       double* const* out) const {
    if (hybrid)
      hybrid->variational_rhs_on_sides(t, z, values.data(), sides.data(), count, S, out,
                                       parameters);
    else
      system.variational_rhs(t, z, values.data(), count, S, out, parameters);
  }
  void rhs_and_variational(double t, const double* z, double* dz, const double* const* S,
                           double* const* out) const {
    if (hybrid)
      hybrid->rhs_and_variational_on_sides(t, z, values.data(), sides.data(), dz, columns, S, out,
                                           parameters);
    else
      system.rhs_and_variational(t, z, values.data(), dz, columns, S, out, parameters);
  }
};

enum class StepOutcome { Step, StopTime, Root };

struct PlannedStep {
  double t = 0.0;  // where the integrator stands internally
  double h = 0.0;  // the step it will attempt next
};

class FlowStepper {
 public:
  virtual ~FlowStepper() = default;
  // Starts a run at t0 from z0 (n entries), the sensitivity columns (call.columns) from `seeds`
  // (n x columns), with roots on the system's switching surfaces.
  virtual void start(double t0, const double* z0, const Eigen::MatrixXd& seeds) = 0;
  // Restarts from the current solution at t (f jumps there; a multistep history is void).
  virtual void restart(double t) = 0;
  // Restarts at t from z and the columns S (n x columns): what a reset and the saltation matrix
  // made of the solution at a crossing.
  virtual void restart_from(double t, const double* z, const Eigen::MatrixXd& S) = 0;
  virtual void set_max_step(double hmax) = 0;  // 0: no limit
  // Where the integrator stands and the step it will attempt next; nullopt before its first step
  // since the last (re)start.
  virtual std::optional<PlannedStep> planned_step() = 0;
  virtual void set_stop_time(double t) = 0;
  // One internal step towards t_end, not past the stop time; `t` is where it ended.
  virtual StepOutcome step(double t_end, double& t) = 0;
  // The state (n entries) and the sensitivity columns where the last step ended.
  virtual const double* state() const = 0;
  virtual void sensitivities(Eigen::MatrixXd& S) = 0;
  // The state and columns at t inside the last step, from the integrator's interpolant.
  virtual void interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) = 0;
  // The state alone at t inside the last step: by default the same interpolant.
  virtual void interpolate_state(double t, Eigen::VectorXd& z) {
    Eigen::MatrixXd S;
    interpolate(t, z, S);
  }
  // Adds the integrator's counters since the last start or restart.
  virtual void collect(FlowStatistics& s) = 0;
  // The integrator's name for messages ("CVode", "ERKStep").
  virtual const char* name() const = 0;
};

std::unique_ptr<FlowStepper> make_cvodes_stepper(FlowCall& call, const FlowOptions& options);
std::unique_ptr<FlowStepper> make_augmented_cvode_stepper(FlowCall& call,
                                                          const FlowOptions& options);
std::unique_ptr<FlowStepper> make_erk_stepper(FlowCall& call, const FlowOptions& options);

// A stepper per number of sensitivity columns, each made by `make(columns)` at the first call
// with that many and kept (the augmented vector's length is fixed per integrator memory; a
// continuation alternates between n and n + 1 columns). Every call goes to the one that the last
// start chose.
std::unique_ptr<FlowStepper> make_stepper_by_columns(
    FlowCall& call, std::function<std::unique_ptr<FlowStepper>(int columns)> make);

// The augmented right-hand side: y = [z; S_0; ...], ydot = [f(t, z); J S_0 (+ df/dp); ...] with
// one call of rhs and one of variational_rhs for all columns. Returns 0, 1 (recoverable: f not
// finite) or -1 (an exception, stored in call.callback_error).
// 0 if the n entries of `dz` are finite; else 1 (recoverable: the integrator retries a smaller
// step), the first such evaluation of the step recorded in call.nonfinite.
// (The check inline, as the loop it replaced in each right-hand side; the description out of line.)
void record_nonfinite_rhs(FlowCall& call, double t, const double* z, const double* dz, int bad);
inline int check_finite_rhs(FlowCall& call, double t, const double* z, const double* dz) {
  const int n = call.system.dimension();
  for (int i = 0; i < n; ++i)
    if (!std::isfinite(dz[i])) {
      record_nonfinite_rhs(call, t, z, dz, i);
      return 1;  // recoverable: the integrator retries a smaller step
    }
  return 0;
}
// Appends to a failure's message what SUNDIALS and check_finite_rhs recorded, and clears both.
void append_failure_details(std::ostringstream& msg, FlowCall& call);

int augmented_rhs(FlowCall& call, double t, const double* y, double* ydot,
                  std::vector<const double*>& columns_in, std::vector<double*>& columns_out);

// The system's switching functions at (t, z): the root function every integrator gives SUNDIALS.
// Returns 0, or -1 (an exception, stored in call.callback_error).
int switching_roots(FlowCall& call, double t, const double* z, double* g);

// The augmented vector v = [z; S_0; ...; S_(c-1)] of an n-dimensional state: set from z0 and the
// seed columns, and its columns read back (z is its first n entries).
void pack_augmented(double* v, const double* z0, const Eigen::MatrixXd& seeds, int n);
void augmented_columns(const double* v, int n, int columns, Eigen::MatrixXd& S);

// The error handler every integrator gives SUNDIALS (user: the FlowCall): keeps the message in
// call.last_error, for the exception that the failed call's check throws.
void record_sundials_error(int code, const char* module, const char* function, char* msg,
                           void* user);

// Throws the stored callback exception if there is one.
void rethrow_callback_error(FlowCall& call);

// Throws std::runtime_error("SUNDIALS: " + what) unless ok (a failed allocation).
void require(bool ok, const std::string& what);

}  // namespace sympathy::detail
