// ARKODE's ERKStep behind a Flow (see flow_stepper.hpp): an explicit embedded Runge-Kutta pair on
// the augmented system y = [z; S_0; ...; S_(c-1)] (the state alone when a call asks for no
// columns), one error test over all of y.
//
// Why: on the metronome model a step of an implicit multistep method with the sensitivity
// module costs 10-11 us, most of it per-vector overhead, and BDF needs ~3,000 steps a period;
// Dormand-Prince 5(4) with the same turning-point step caps needs ~480 steps a period at ~3 us
// (NUMERICS.md: the anti-phase k-branch 13x faster at error 8e-10). Without the caps its error
// sticks at 1.9e-6 (the escapement pulse); the Flow applies them as for CVODES. Explicit: a stiff
// platform (large k, c) forces steps down to its stability limit (still 7x faster than BDF at
// c = 50 N s/m in the probe, at 2.2x the steps).
//
// Outputs inside a step come from ARKODE's Hermite interpolant (degree min(order - 1, 5): 4 for
// Dormand-Prince), which evaluates the whole augmented right-hand side once more for an output:
// 801 samples of a period that way cost 24% of the fast preset's branch. The state alone
// (interpolate_state: a branch's scales and descriptions) comes from the cubic Hermite interpolant
// of the step's ends and rates instead, two evaluations of f (the state's, no columns) a step:
// error below h^4 max|z''''| / 384, about 3e-9 relative at Dormand-Prince's longest steps on the
// metronome model (3 ms, 11 rad/s), within the flow's own tolerance. Switching surfaces are
// ARKODE's root functions (ERKStepRootInit), the integrator restarted at each (ERKStepReInit) as
// CVODE is.
#include <arkode/arkode_erkstep.h>
#include <nvector/nvector_serial.h>

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "flow_stepper.hpp"
#include "vector_ops.hpp"

namespace sympathy::detail {

namespace {

class ErkStepper final : public FlowStepper {
 public:
  ErkStepper(FlowCall& call, const FlowOptions& options, int columns);
  ~ErkStepper() override;
  ErkStepper(const ErkStepper&) = delete;
  ErkStepper& operator=(const ErkStepper&) = delete;

  void start(double t0, const double* z0, const Eigen::MatrixXd& seeds) override;
  void restart(double t) override {
    t_now = t;
    check(ERKStepReInit(mem, rhs, t, y), "ERKStepReInit");
  }
  void restart_from(double t, const double* z, const Eigen::MatrixXd& S) override {
    pack_augmented(N_VGetArrayPointer(y), z, S, call.system.dimension());
    restart(t);
  }
  void set_max_step(double hmax) override {
    check(ERKStepSetMaxStep(mem, hmax), "ERKStepSetMaxStep");
  }
  std::optional<PlannedStep> planned_step() override;
  void set_stop_time(double t) override { check(ERKStepSetStopTime(mem, t), "ERKStepSetStopTime"); }
  StepOutcome step(double t_end, double& t) override;
  const double* state() const override { return N_VGetArrayPointer(y); }
  void sensitivities(Eigen::MatrixXd& S) override { columns_of(N_VGetArrayPointer(y), S); }
  void interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) override;
  void interpolate_state(double t, Eigen::VectorXd& z) override;
  void collect(FlowStatistics& s) override;
  const char* name() const override { return "ERKStep"; }

 private:
  void create(const FlowOptions& options);  // the SUNDIALS objects
  void release();                           // ... freed
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
  static int roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user);
  void columns_of(const double* v, Eigen::MatrixXd& S) const {
    augmented_columns(v, call.system.dimension(), columns, S);
  }
  [[noreturn]] void fail(int flag, const char* function);
  void check(int flag, const char* function) {
    if (flag < 0) fail(flag, function);
  }

  FlowCall& call;
  int columns;
  double t_now = 0.0;
  // The state where the last step began (t_before), for interpolate_state; the rates at both ends
  // are evaluated on its first use in a step (the step that ended at rates_at).
  double t_before = 0.0;
  Eigen::VectorXd z_before, rate_before, rate_after;
  double rates_at = std::numeric_limits<double>::quiet_NaN();
  int root_count = -1;
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr, out = nullptr;
  std::vector<const double*> columns_in;
  std::vector<double*> columns_out;
};

ARKODE_ERKTableID table_id(ExplicitTable table) {
  switch (table) {
    case ExplicitTable::DormandPrince:
      return ARKODE_DORMAND_PRINCE_7_4_5;
    case ExplicitTable::Verner:
      return ARKODE_VERNER_8_5_6;
  }
  return ARKODE_DORMAND_PRINCE_7_4_5;
}

ErkStepper::ErkStepper(FlowCall& flow_call, const FlowOptions& options, int c)
    : call(flow_call), columns(c) {
  // A constructor that throws runs no destructor: free what was made so far.
  try {
    create(options);
  } catch (...) {
    release();
    throw;
  }
}

void ErkStepper::create(const FlowOptions& options) {
  const int size = call.system.dimension() * (1 + columns);
  require(SUNContext_Create(nullptr, &ctx) == 0, "SUNContext_Create failed");
  y = N_VNew_Serial(size, ctx);
  require(y != nullptr, "N_VNew_Serial failed");
  require(N_VEnableFusedOps_Serial(y, SUNTRUE) == 0, "N_VEnableFusedOps_Serial failed");
  use_project_vector_ops(y);  // vector_ops.hpp: Debian's linear combination is 5x slower
  N_VConst(0.0, y);
  out = N_VClone(y);
  require(out != nullptr, "N_VClone failed");
  mem = ERKStepCreate(rhs, 0.0, y, ctx);
  require(mem != nullptr, "ERKStepCreate failed");
  check(ERKStepSetErrHandlerFn(mem, record_sundials_error, &call), "ERKStepSetErrHandlerFn");
  check(ERKStepSetUserData(mem, this), "ERKStepSetUserData");
  check(ERKStepSStolerances(mem, options.rtol, options.atol), "ERKStepSStolerances");
  check(ERKStepSetTableNum(mem, table_id(options.explicit_table)), "ERKStepSetTableNum");
  check(ERKStepSetMaxNumSteps(mem, options.max_steps), "ERKStepSetMaxNumSteps");
}

ErkStepper::~ErkStepper() {
  release();
}

// Frees every SUNDIALS object made, in reverse order of creation; once: from the destructor, or
// from a constructor that failed.
void ErkStepper::release() {
  if (mem) ERKStepFree(&mem);
  if (out) N_VDestroy(out);
  if (y) N_VDestroy(y);
  if (ctx) SUNContext_Free(&ctx);
}

int ErkStepper::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& st = *static_cast<ErkStepper*>(user);
  return augmented_rhs(st.call, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), st.columns_in,
                       st.columns_out);
}

int ErkStepper::roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user) {
  return switching_roots(static_cast<ErkStepper*>(user)->call, t, N_VGetArrayPointer(y), g);
}

void ErkStepper::fail(int flag, const char* function) {
  rethrow_callback_error(call);
  char* flag_name = ERKStepGetReturnFlagName(flag);  // malloc'd by ARKODE
  std::ostringstream msg;
  msg << function << " failed at t = " << t_now << ": " << (flag_name ? flag_name : "?");
  std::free(flag_name);
  append_failure_details(msg, call);
  throw IntegrationError(msg.str(), t_now);
}

void ErkStepper::start(double t0, const double* z0, const Eigen::MatrixXd& seeds) {
  const int n = call.system.dimension();
  t_now = t0;
  pack_augmented(N_VGetArrayPointer(y), z0, seeds, n);
  check(ERKStepReInit(mem, rhs, t0, y), "ERKStepReInit");
  const int count = call.system.switching_count();
  if (count != root_count) {
    check(ERKStepRootInit(mem, count, count > 0 ? roots : nullptr), "ERKStepRootInit");
    if (count > 0) check(ERKStepSetNoInactiveRootWarn(mem), "ERKStepSetNoInactiveRootWarn");
    root_count = count;
  }
  if (count > 0 && !call.root_directions.empty())
    check(ERKStepSetRootDirection(mem, call.root_directions.data()), "ERKStepSetRootDirection");
}

std::optional<PlannedStep> ErkStepper::planned_step() {
  long steps = 0;
  check(ERKStepGetNumSteps(mem, &steps), "ERKStepGetNumSteps");
  if (steps == 0) return std::nullopt;
  PlannedStep p;
  check(ERKStepGetCurrentStep(mem, &p.h), "ERKStepGetCurrentStep");
  check(ERKStepGetCurrentTime(mem, &p.t), "ERKStepGetCurrentTime");
  return p;
}

StepOutcome ErkStepper::step(double t_end, double& t) {
  t_before = t_now;
  z_before = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(y), call.system.dimension());
  rates_at = std::numeric_limits<double>::quiet_NaN();
  call.nonfinite.clear();
  const int flag = ERKStepEvolve(mem, t_end, y, &t, ARK_ONE_STEP);
  t_now = t;
  if (flag < 0 || call.callback_error) fail(flag, "ERKStepEvolve");
  if (flag == ARK_ROOT_RETURN) return StepOutcome::Root;
  if (flag == ARK_TSTOP_RETURN) return StepOutcome::StopTime;
  return StepOutcome::Step;
}

void ErkStepper::interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) {
  const int n = call.system.dimension();
  check(ERKStepGetDky(mem, t, 0, out), "ERKStepGetDky");
  z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out), n);
  columns_of(N_VGetArrayPointer(out), S);
}

void ErkStepper::interpolate_state(double t, Eigen::VectorXd& z) {
  const int n = call.system.dimension();
  const double h = t_now - t_before;
  const Eigen::Map<const Eigen::VectorXd> z_after(N_VGetArrayPointer(y), n);
  if (!(h > 0.0)) {
    z = z_after;
    return;
  }
  if (!(rates_at == t_now)) {
    rate_before.resize(n);
    rate_after.resize(n);
    call.rhs(t_before, z_before.data(), rate_before.data());
    call.rhs(t_now, z_after.data(), rate_after.data());
    rates_at = t_now;
  }
  // The cubic Hermite basis at s = (t - t_before) / h.
  const double s = std::clamp((t - t_before) / h, 0.0, 1.0);
  const double s2 = s * s, s3 = s2 * s;
  z = (2 * s3 - 3 * s2 + 1) * z_before + (s3 - 2 * s2 + s) * h * rate_before +
      (3 * s2 - 2 * s3) * z_after + (s3 - s2) * h * rate_after;
}

void ErkStepper::collect(FlowStatistics& s) {
  long v = 0;
  if (ERKStepGetNumSteps(mem, &v) == ARK_SUCCESS) s.steps += v;
  if (ERKStepGetNumRhsEvals(mem, &v) == ARK_SUCCESS) {
    s.rhs_evaluations += v;
    if (columns > 0) s.variational_evaluations += v;  // each evaluation includes all columns
  }
  if (ERKStepGetNumErrTestFails(mem, &v) == ARK_SUCCESS) s.error_test_failures += v;
}

}  // namespace

std::unique_ptr<FlowStepper> make_erk_stepper(FlowCall& call, const FlowOptions& options) {
  return make_stepper_by_columns(call, [&call, options](int columns) {
    return std::unique_ptr<FlowStepper>(std::make_unique<ErkStepper>(call, options, columns));
  });
}

}  // namespace sympathy::detail
