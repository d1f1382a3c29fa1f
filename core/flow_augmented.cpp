// CVODE on the augmented system behind a Flow (see flow_stepper.hpp): the state and its
// sensitivity columns as one N_Vector y = [z; S_0; ...; S_(c-1)] of n (1 + c) entries, its
// right-hand side one call of rhs and one of variational_rhs for all columns. One error test
// over all of y, as the forward-sensitivity module's with its sensitivities in the error test.
//
// Why: CVODES's sensitivity module pays a per-vector overhead on each of its c + 1 short
// vectors every step (10-15 us a step for n = 6, c = 7, against 1.5-3 us for the state alone;
// NUMERICS.md); one long vector pays it once. The probe measured the row setup's anti-phase
// k-branch 2.9x faster at equal error with Adams and fixed-point iteration.
//
// With Newton iteration (BDF) the linear solver is dense on all n (1 + c) unknowns with the
// Jacobian approximated by its block diagonal (J in every block; the coupling d(J S)/dz left
// out, as a modified Newton iteration may): affordable for small n only. Plain runs (no columns)
// are CVODES's on the state, as with the forward-sensitivity module.
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>

#include <algorithm>
#include <sstream>

#include "flow_stepper.hpp"
#include "vector_ops.hpp"

namespace sympathy::detail {

namespace {

class AugmentedCvode final : public FlowStepper {
 public:
  AugmentedCvode(FlowCall& call, const FlowOptions& options, int columns);
  ~AugmentedCvode() override;
  AugmentedCvode(const AugmentedCvode&) = delete;
  AugmentedCvode& operator=(const AugmentedCvode&) = delete;

  void start(double t0, const double* z0, const Eigen::MatrixXd& seeds) override;
  void restart(double t) override {
    t_now = t;
    check(CVodeReInit(mem, t, y), "CVodeReInit");
  }
  void restart_from(double t, const double* z, const Eigen::MatrixXd& S) override {
    pack_augmented(N_VGetArrayPointer(y), z, S, call.system.dimension());
    restart(t);
  }
  void set_max_step(double hmax) override { check(CVodeSetMaxStep(mem, hmax), "CVodeSetMaxStep"); }
  std::optional<PlannedStep> planned_step() override;
  void set_stop_time(double t) override { check(CVodeSetStopTime(mem, t), "CVodeSetStopTime"); }
  StepOutcome step(double t_end, double& t) override;
  const double* state() const override { return N_VGetArrayPointer(y); }
  void sensitivities(Eigen::MatrixXd& S) override { columns_of(N_VGetArrayPointer(y), S); }
  void interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) override;
  // The state's part of the interpolant, the columns not copied out.
  void interpolate_state(double t, Eigen::VectorXd& z) override;
  void collect(FlowStatistics& s) override;
  const char* name() const override { return "CVode"; }

 private:
  void create(const FlowOptions& options);  // the SUNDIALS objects
  void release();                           // ... freed
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
  static int block_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* user,
                            N_Vector, N_Vector, N_Vector);
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
  int root_count = -1;
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr, out = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver nonlinear_solver = nullptr;
  Eigen::MatrixXd jacobian;
  std::vector<const double*> columns_in;
  std::vector<double*> columns_out;
};

AugmentedCvode::AugmentedCvode(FlowCall& flow_call, const FlowOptions& options, int c)
    : call(flow_call), columns(c) {
  // A constructor that throws runs no destructor: free what was made so far.
  try {
    create(options);
  } catch (...) {
    release();
    throw;
  }
}

void AugmentedCvode::create(const FlowOptions& options) {
  const int n = call.system.dimension();
  const int size = n * (1 + columns);
  require(SUNContext_Create(nullptr, &ctx) == 0, "SUNContext_Create failed");
  y = N_VNew_Serial(size, ctx);
  require(y != nullptr, "N_VNew_Serial failed");
  require(N_VEnableFusedOps_Serial(y, SUNTRUE) == 0, "N_VEnableFusedOps_Serial failed");
  use_project_vector_ops(y);  // vector_ops.hpp: Debian's linear combination is 5x slower
  N_VConst(0.0, y);
  out = N_VClone(y);
  require(out != nullptr, "N_VClone failed");
  mem = CVodeCreate(options.method == Method::BDF ? CV_BDF : CV_ADAMS, ctx);
  require(mem != nullptr, "CVodeCreate failed");
  check(CVodeSetErrHandlerFn(mem, record_sundials_error, &call), "CVodeSetErrHandlerFn");
  check(CVodeInit(mem, rhs, 0.0, y), "CVodeInit");
  check(CVodeSetUserData(mem, this), "CVodeSetUserData");
  check(CVodeSStolerances(mem, options.rtol, options.atol), "CVodeSStolerances");
  check(CVodeSetMaxNumSteps(mem, options.max_steps), "CVodeSetMaxNumSteps");
  if (options.nonlinear_solver == NonlinearSolver::FixedPoint) {
    nonlinear_solver = SUNNonlinSol_FixedPoint(y, 0, ctx);
    require(nonlinear_solver != nullptr, "SUNNonlinSol_FixedPoint failed");
    check(CVodeSetNonlinearSolver(mem, nonlinear_solver), "CVodeSetNonlinearSolver");
    return;
  }
  nonlinear_solver = SUNNonlinSol_Newton(y, ctx);
  require(nonlinear_solver != nullptr, "SUNNonlinSol_Newton failed");
  check(CVodeSetNonlinearSolver(mem, nonlinear_solver), "CVodeSetNonlinearSolver");
  matrix = SUNDenseMatrix(size, size, ctx);
  require(matrix != nullptr, "SUNDenseMatrix failed");
  linear_solver = SUNLinSol_Dense(y, matrix, ctx);
  require(linear_solver != nullptr, "SUNLinSol_Dense failed");
  check(CVodeSetLinearSolver(mem, linear_solver, matrix), "CVodeSetLinearSolver");
  if (call.system.differentiable() && options.derivatives == Derivatives::Model)
    check(CVodeSetJacFn(mem, block_jacobian), "CVodeSetJacFn");
}

AugmentedCvode::~AugmentedCvode() {
  release();
}

// Frees every SUNDIALS object made, in reverse order of creation; once: from the destructor, or
// from a constructor that failed.
void AugmentedCvode::release() {
  if (mem) CVodeFree(&mem);
  if (nonlinear_solver) SUNNonlinSolFree(nonlinear_solver);
  if (linear_solver) SUNLinSolFree(linear_solver);
  if (matrix) SUNMatDestroy(matrix);
  if (out) N_VDestroy(out);
  if (y) N_VDestroy(y);
  if (ctx) SUNContext_Free(&ctx);
}

int AugmentedCvode::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& st = *static_cast<AugmentedCvode*>(user);
  return augmented_rhs(st.call, t, N_VGetArrayPointer(y), N_VGetArrayPointer(ydot), st.columns_in,
                       st.columns_out);
}

int AugmentedCvode::block_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* user,
                                   N_Vector, N_Vector, N_Vector) {
  auto& st = *static_cast<AugmentedCvode*>(user);
  try {
    const int n = st.call.system.dimension();
    const int size = n * (1 + st.columns);
    st.call.jacobian(t, N_VGetArrayPointer(y), st.jacobian);
    Eigen::Map<Eigen::MatrixXd> out(SM_DATA_D(jac), size, size);
    out.setZero();
    for (int b = 0; b <= st.columns; ++b) out.block(b * n, b * n, n, n) = st.jacobian;
    return 0;
  } catch (...) {
    st.call.callback_error = std::current_exception();
    return -1;
  }
}

int AugmentedCvode::roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user) {
  return switching_roots(static_cast<AugmentedCvode*>(user)->call, t, N_VGetArrayPointer(y), g);
}

void AugmentedCvode::fail(int flag, const char* function) {
  rethrow_callback_error(call);
  std::ostringstream msg;
  msg << function << " failed at t = " << t_now << ": " << CVodeGetReturnFlagName(flag);
  append_failure_details(msg, call);
  throw IntegrationError(msg.str(), t_now);
}

void AugmentedCvode::start(double t0, const double* z0, const Eigen::MatrixXd& seeds) {
  const int n = call.system.dimension();
  t_now = t0;
  pack_augmented(N_VGetArrayPointer(y), z0, seeds, n);
  check(CVodeReInit(mem, t0, y), "CVodeReInit");
  const int count = call.system.switching_count();
  if (count != root_count) {
    check(CVodeRootInit(mem, count, count > 0 ? roots : nullptr), "CVodeRootInit");
    if (count > 0) check(CVodeSetNoInactiveRootWarn(mem), "CVodeSetNoInactiveRootWarn");
    root_count = count;
  }
  if (count > 0 && !call.root_directions.empty())
    check(CVodeSetRootDirection(mem, call.root_directions.data()), "CVodeSetRootDirection");
}

std::optional<PlannedStep> AugmentedCvode::planned_step() {
  long steps = 0;
  check(CVodeGetNumSteps(mem, &steps), "CVodeGetNumSteps");
  if (steps == 0) return std::nullopt;
  PlannedStep p;
  check(CVodeGetCurrentStep(mem, &p.h), "CVodeGetCurrentStep");
  check(CVodeGetCurrentTime(mem, &p.t), "CVodeGetCurrentTime");
  return p;
}

StepOutcome AugmentedCvode::step(double t_end, double& t) {
  call.nonfinite.clear();
  const int flag = CVode(mem, t_end, y, &t, CV_ONE_STEP);
  t_now = t;
  if (flag < 0 || call.callback_error) fail(flag, "CVode");
  if (flag == CV_ROOT_RETURN) return StepOutcome::Root;
  if (flag == CV_TSTOP_RETURN) return StepOutcome::StopTime;
  return StepOutcome::Step;
}

void AugmentedCvode::interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) {
  const int n = call.system.dimension();
  check(CVodeGetDky(mem, t, 0, out), "CVodeGetDky");
  z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out), n);
  columns_of(N_VGetArrayPointer(out), S);
}

void AugmentedCvode::interpolate_state(double t, Eigen::VectorXd& z) {
  check(CVodeGetDky(mem, t, 0, out), "CVodeGetDky");
  z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out), call.system.dimension());
}

void AugmentedCvode::collect(FlowStatistics& s) {
  long v = 0;
  if (CVodeGetNumSteps(mem, &v) == CV_SUCCESS) s.steps += v;
  if (CVodeGetNumRhsEvals(mem, &v) == CV_SUCCESS) {
    s.rhs_evaluations += v;
    s.variational_evaluations += v;  // each evaluation includes all columns
  }
  if (CVodeGetNumLinSolvSetups(mem, &v) == CV_SUCCESS) s.linear_setups += v;
  if (CVodeGetNumErrTestFails(mem, &v) == CV_SUCCESS) s.error_test_failures += v;
  if (CVodeGetNumNonlinSolvIters(mem, &v) == CV_SUCCESS) s.nonlinear_iterations += v;
  if (linear_solver && CVodeGetNumJacEvals(mem, &v) == CV_SUCCESS) s.jacobian_evaluations += v;
}

}  // namespace

std::unique_ptr<FlowStepper> make_augmented_cvode_stepper(FlowCall& call,
                                                          const FlowOptions& options) {
  return make_stepper_by_columns(call, [&call, options](int columns) {
    return columns == 0 ? make_cvodes_stepper(call, options)
                        : std::unique_ptr<FlowStepper>(
                              std::make_unique<AugmentedCvode>(call, options, columns));
  });
}

}  // namespace sympathy::detail
