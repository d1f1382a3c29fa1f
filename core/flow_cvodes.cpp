// The CVODES integrator with its forward-sensitivity module behind a Flow (see flow_stepper.hpp):
// the state in one N_Vector, each sensitivity column in one more, BDF or Adams, the Newton
// iteration's linear solver dense, KLU or structured (sparse plus low rank). One CVODES memory
// serves every call, its sensitivity module switched on for the calls that ask for columns.
#include <cvodes/cvodes.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>
#include <sunnonlinsol/sunnonlinsol_fixedpoint.h>
#include <sunnonlinsol/sunnonlinsol_newton.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "flow_stepper.hpp"
#include "sympathy/core/low_rank_solver.hpp"
#include "vector_ops.hpp"

namespace sympathy::detail {

// The structured linear solver (LinearSolver::Structured) as a SUNMatrix and a SUNLinearSolver of
// type SUNLINEARSOLVER_DIRECT, so that CVODES's own setup logic applies as for the dense and KLU
// solvers: it decides when to evaluate the Jacobian (and keeps a copy, savedJ, to reuse), forms
// A = I - gamma J through the matrix operations, calls the solver's setup to factor A, and scales
// solutions by 2 / (1 + gamma ratio) when gamma has changed since. (A matrix-embedded solver,
// which CVODES gives no matrix, was tried first: CVODES then never calls its setup, resets its
// convergence-rate estimates every step and takes a weighted norm of every right-hand side;
// sensitivity corrector iterations rose by ~45% over the dense solver's on many16.)
//
namespace {

// The matrix: A = identity * I + scale * (S + U W^T), the Jacobian held in low-rank form.
struct LowRankMatrix {
  LowRankJacobian jacobian;
  double identity = 0.0;
  double scale = 1.0;
};

// The linear solver's state: the factorization of A = identity * (I - gamma J).
struct StructuredSolver {
  FlowCall* call;  // for storing a callback's exception
  LowRankSolver solver;
  double inverse_identity = 1.0;
  StructuredSolver(FlowCall* c, const LowRankJacobian& structure) : call(c), solver(structure) {}
};

}  // namespace

namespace {

// SUNMatrix operations of LowRankMatrix: what CVODES's linear solver interface uses (clone for
// its saved Jacobian, zero, copy, A = c A + I) and destroy.
LowRankMatrix& low_rank(SUNMatrix a) {
  return *static_cast<LowRankMatrix*>(a->content);
}
SUNMatrix_ID low_rank_id(SUNMatrix) {
  return SUNMATRIX_CUSTOM;
}
void low_rank_destroy(SUNMatrix a) {
  if (!a) return;
  delete static_cast<LowRankMatrix*>(a->content);
  a->content = nullptr;
  SUNMatFreeEmpty(a);
}
SUNMatrix low_rank_clone(SUNMatrix a) {
  SUNMatrix b = SUNMatNewEmpty(a->sunctx);
  if (!b) return nullptr;
  if (SUNMatCopyOps(a, b) != 0) {
    SUNMatFreeEmpty(b);
    return nullptr;
  }
  try {
    b->content = new LowRankMatrix(low_rank(a));
  } catch (...) {
    SUNMatFreeEmpty(b);
    return nullptr;
  }
  return b;
}
int low_rank_zero(SUNMatrix a) {
  auto& m = low_rank(a);
  std::fill(m.jacobian.values.begin(), m.jacobian.values.end(), 0.0);
  m.jacobian.U.setZero();
  m.jacobian.W.setZero();
  m.identity = 0.0;
  m.scale = 1.0;
  return 0;
}
int low_rank_copy(SUNMatrix from, SUNMatrix to) {
  auto& a = low_rank(from);
  auto& b = low_rank(to);
  b.jacobian.values = a.jacobian.values;
  b.jacobian.U = a.jacobian.U;
  b.jacobian.W = a.jacobian.W;
  b.identity = a.identity;
  b.scale = a.scale;
  return 0;
}
int low_rank_scale_add_identity(sunrealtype c, SUNMatrix a) {
  auto& m = low_rank(a);
  m.identity = c * m.identity + 1.0;
  m.scale *= c;
  return 0;
}

SUNMatrix new_low_rank_matrix(const LowRankJacobian& structure, SUNContext ctx) {
  SUNMatrix a = SUNMatNewEmpty(ctx);
  if (!a) return nullptr;
  a->ops->getid = low_rank_id;
  a->ops->clone = low_rank_clone;
  a->ops->destroy = low_rank_destroy;
  a->ops->zero = low_rank_zero;
  a->ops->copy = low_rank_copy;
  a->ops->scaleaddi = low_rank_scale_add_identity;
  try {
    a->content = new LowRankMatrix{structure};
  } catch (...) {
    SUNMatFreeEmpty(a);
    throw;
  }
  return a;
}

// SUNLinearSolver operations of the structured solver (content: a StructuredSolver, owned by
// the stepper).
StructuredSolver& structured(SUNLinearSolver s) {
  return *static_cast<StructuredSolver*>(s->content);
}
SUNLinearSolver_Type structured_type(SUNLinearSolver) {
  return SUNLINEARSOLVER_DIRECT;
}
SUNLinearSolver_ID structured_id(SUNLinearSolver) {
  return SUNLINEARSOLVER_CUSTOM;
}
int structured_initialize(SUNLinearSolver) {
  return SUNLS_SUCCESS;
}
int structured_free(SUNLinearSolver s) {
  if (!s) return SUNLS_SUCCESS;
  s->content = nullptr;  // owned by the stepper
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

namespace {

class CvodesStepper;

// C callbacks. They never let a C++ exception cross CVODES: it is stored and rethrown after
// CVode returns.
struct CvodesCallbacks {
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user);
  static int dense_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* user,
                            N_Vector, N_Vector, N_Vector);
  static int sparse_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* user,
                             N_Vector, N_Vector, N_Vector);
  static int low_rank_jacobian(sunrealtype t, N_Vector y, N_Vector, SUNMatrix jac, void* user,
                               N_Vector, N_Vector, N_Vector);
  static int sensitivity_rhs(int columns, sunrealtype t, N_Vector y, N_Vector, N_Vector* yS,
                             N_Vector* ySdot, void* user, N_Vector, N_Vector);
  static int roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user);
  static int structured_setup(SUNLinearSolver s, SUNMatrix a);
  static int structured_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, sunrealtype);
};

// Every SUNDIALS object of one integrator, freed in reverse order of creation.
class CvodesStepper final : public FlowStepper {
 public:
  CvodesStepper(FlowCall& call, const FlowOptions& options);
  ~CvodesStepper() override;
  CvodesStepper(const CvodesStepper&) = delete;
  CvodesStepper& operator=(const CvodesStepper&) = delete;

  void start(double t0, const double* z0, const Eigen::MatrixXd& seeds) override;
  void restart(double t) override;
  void restart_from(double t, const double* z, const Eigen::MatrixXd& S) override;
  void set_max_step(double hmax) override;
  std::optional<PlannedStep> planned_step() override;
  void set_stop_time(double t) override;
  StepOutcome step(double t_end, double& t) override;
  const double* state() const override { return N_VGetArrayPointer(y); }
  void sensitivities(Eigen::MatrixXd& S) override;
  void interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) override;
  // The state's interpolant alone (no CVodeGetSensDky).
  void interpolate_state(double t, Eigen::VectorXd& z) override;
  void collect(FlowStatistics& s) override;
  const char* name() const override { return "CVode"; }

 private:
  void create();   // the SUNDIALS objects, from the options
  void release();  // ... freed
  friend struct CvodesCallbacks;
  [[noreturn]] void fail(int flag, const char* function);
  void check(int flag, const char* function) {
    if (flag < 0) fail(flag, function);
  }
  void start_sensitivities(const Eigen::MatrixXd& seeds);

  FlowCall& call;
  FlowOptions options;
  double t_now = 0.0;
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr;
  N_Vector out = nullptr;  // interpolated state
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver nonlinear_solver = nullptr;
  SUNNonlinearSolver sens_nonlinear_solver = nullptr;
  N_Vector* yS = nullptr;
  N_Vector* out_sens = nullptr;   // interpolated columns
  int sens_columns = 0;           // as allocated by CVodeSensInit
  bool sens_initialized = false;  // CVodeSensInit called for sens_columns
  bool sens_on = false;
  int root_count = -1;  // as given to CVodeRootInit

  // Sparse (CSC) pattern of the Jacobian for KLU, and where each entry sits in the dense one.
  std::vector<sunindextype> column_starts, row_indices;
  std::vector<int> dense_positions;
  Eigen::MatrixXd jacobian;
  std::vector<const double*> columns_in;
  std::vector<double*> columns_out;
  std::vector<double> dq_parameters, dq_scales;  // for CVODES's difference quotients
  std::vector<int> dq_list;
  std::unique_ptr<StructuredSolver> structured;  // LinearSolver::Structured; read by linear_solver
};

int CvodesCallbacks::rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
  auto& call = static_cast<CvodesStepper*>(user)->call;
  try {
    double* dz = N_VGetArrayPointer(ydot);
    call.rhs(t, N_VGetArrayPointer(y), dz);
    return check_finite_rhs(call, t, N_VGetArrayPointer(y), dz);
  } catch (...) {
    call.callback_error = std::current_exception();
    return -1;
  }
}

int CvodesCallbacks::dense_jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac,
                                    void* user, N_Vector, N_Vector, N_Vector) {
  auto& st = *static_cast<CvodesStepper*>(user);
  try {
    const int n = st.call.system.dimension();
    Eigen::Map<Eigen::MatrixXd> out(SM_DATA_D(jac), n, n);
    st.call.jacobian(t, N_VGetArrayPointer(y), st.jacobian);
    out = st.jacobian;
    return 0;
  } catch (...) {
    st.call.callback_error = std::current_exception();
    return -1;
  }
}

int CvodesCallbacks::sparse_jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac,
                                     void* user, N_Vector, N_Vector, N_Vector) {
  auto& st = *static_cast<CvodesStepper*>(user);
  try {
    st.call.jacobian(t, N_VGetArrayPointer(y), st.jacobian);
    std::copy(st.column_starts.begin(), st.column_starts.end(), SM_INDEXPTRS_S(jac));
    std::copy(st.row_indices.begin(), st.row_indices.end(), SM_INDEXVALS_S(jac));
    double* values = SM_DATA_S(jac);
    const double* dense = st.jacobian.data();
    for (std::size_t k = 0; k < st.dense_positions.size(); ++k)
      values[k] = dense[st.dense_positions[k]];
    return 0;
  } catch (...) {
    st.call.callback_error = std::current_exception();
    return -1;
  }
}

int CvodesCallbacks::sensitivity_rhs(int columns, sunrealtype t, N_Vector y, N_Vector /*ydot*/,
                                     N_Vector* yS, N_Vector* ySdot, void* user, N_Vector,
                                     N_Vector) {
  auto& st = *static_cast<CvodesStepper*>(user);
  try {
    for (int j = 0; j < columns; ++j) {
      st.columns_in[j] = N_VGetArrayPointer(yS[j]);
      st.columns_out[j] = N_VGetArrayPointer(ySdot[j]);
    }
    st.call.variational_rhs(t, N_VGetArrayPointer(y), columns, st.columns_in.data(),
                            st.columns_out.data());
    return 0;
  } catch (...) {
    st.call.callback_error = std::current_exception();
    return -1;
  }
}

int CvodesCallbacks::roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user) {
  return switching_roots(static_cast<CvodesStepper*>(user)->call, t, N_VGetArrayPointer(y), g);
}

// The Jacobian in low-rank form, written into a LowRankMatrix.
int CvodesCallbacks::low_rank_jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac,
                                       void* user, N_Vector, N_Vector, N_Vector) {
  auto& call = static_cast<CvodesStepper*>(user)->call;
  try {
    auto& m = *static_cast<LowRankMatrix*>(jac->content);
    if (!call.system.low_rank_jacobian(t, N_VGetArrayPointer(y), call.values.data(), m.jacobian))
      throw std::logic_error("the system stopped providing its low-rank Jacobian");
    m.identity = 0.0;
    m.scale = 1.0;
    return 0;
  } catch (...) {
    call.callback_error = std::current_exception();
    return -1;
  }
}

// Factors A = identity * I + scale * J = identity * (I - gamma J); a singular A is a recoverable
// failure (CVODES retries with a smaller step), as for the dense LU.
int CvodesCallbacks::structured_setup(SUNLinearSolver s, SUNMatrix a) {
  auto& st = structured(s);
  try {
    const auto& m = low_rank(a);
    if (!(m.identity != 0.0)) return SUNLS_ILL_INPUT;
    st.inverse_identity = 1.0 / m.identity;
    return st.solver.factor(m.jacobian, -m.scale / m.identity) ? SUNLS_SUCCESS : SUNLS_LUFACT_FAIL;
  } catch (...) {
    st.call->callback_error = std::current_exception();
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

int CvodesCallbacks::structured_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b,
                                      sunrealtype) {
  auto& st = structured(s);
  try {
    if (x != b) N_VScale(1.0, b, x);
    st.solver.solve(N_VGetArrayPointer(x));
    if (st.inverse_identity != 1.0) N_VScale(st.inverse_identity, x, x);
    return SUNLS_SUCCESS;
  } catch (...) {
    st.call->callback_error = std::current_exception();
    return SUNLS_PACKAGE_FAIL_UNREC;
  }
}

void CvodesStepper::fail(int flag, const char* function) {
  rethrow_callback_error(call);
  std::ostringstream msg;
  msg << function << " failed at t = " << t_now << ": " << CVodeGetReturnFlagName(flag);
  append_failure_details(msg, call);
  throw IntegrationError(msg.str(), t_now);
}

#define SYMPATHY_CHECK(call) check((call), #call)

CvodesStepper::CvodesStepper(FlowCall& flow_call, const FlowOptions& flow_options)
    : call(flow_call), options(flow_options) {
  // A constructor that throws runs no destructor: free what was made so far.
  try {
    create();
  } catch (...) {
    release();
    throw;
  }
}

void CvodesStepper::create() {
  const auto& system = call.system;
  const int n = system.dimension();
  require(SUNContext_Create(nullptr, &ctx) == 0, "SUNContext_Create failed");
  y = N_VNew_Serial(n, ctx);
  require(y != nullptr, "N_VNew_Serial failed");
  // Fused vector operations (one pass over the memory for a linear combination of several
  // vectors, which the sensitivity columns are): 6-7% less time per step measured on the row
  // setup's branches; clones (the sensitivity columns) inherit them.
  require(N_VEnableFusedOps_Serial(y, SUNTRUE) == 0, "N_VEnableFusedOps_Serial failed");
  use_project_vector_ops(y);  // vector_ops.hpp: Debian's linear combination is 5x slower
  N_VConst(0.0, y);
  out = N_VClone(y);
  require(out != nullptr, "N_VClone failed");
  mem = CVodeCreate(options.method == Method::BDF ? CV_BDF : CV_ADAMS, ctx);
  require(mem != nullptr, "CVodeCreate failed");
  SYMPATHY_CHECK(CVodeSetErrHandlerFn(mem, record_sundials_error, &call));
  SYMPATHY_CHECK(CVodeInit(mem, CvodesCallbacks::rhs, 0.0, y));
  SYMPATHY_CHECK(CVodeSetUserData(mem, this));
  SYMPATHY_CHECK(CVodeSStolerances(mem, options.rtol, options.atol));
  SYMPATHY_CHECK(CVodeSetMaxNumSteps(mem, options.max_steps));

  if (options.nonlinear_solver == NonlinearSolver::FixedPoint) {
    nonlinear_solver = SUNNonlinSol_FixedPoint(y, 0, ctx);
    require(nonlinear_solver != nullptr, "SUNNonlinSol_FixedPoint failed");
    SYMPATHY_CHECK(CVodeSetNonlinearSolver(mem, nonlinear_solver));
    return;
  }
  nonlinear_solver = SUNNonlinSol_Newton(y, ctx);
  require(nonlinear_solver != nullptr, "SUNNonlinSol_Newton failed");
  SYMPATHY_CHECK(CVodeSetNonlinearSolver(mem, nonlinear_solver));
  if (options.linear_solver == LinearSolver::KLU) {
    if (!system.differentiable() || options.derivatives != Derivatives::Model)
      throw std::invalid_argument("the KLU linear solver needs the system's Jacobian");
    auto entries = system.jacobian_pattern();
    if (entries.empty())
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) entries.emplace_back(i, j);
    // Compressed sparse columns, entries checked and repeats merged (a sparse part of rank 0).
    const LowRankJacobian pattern(n, 0, std::move(entries));
    column_starts.assign(pattern.column_starts.begin(), pattern.column_starts.end());
    row_indices.assign(pattern.row_indices.begin(), pattern.row_indices.end());
    for (int j = 0; j < n; ++j)
      for (int k = pattern.column_starts[j]; k < pattern.column_starts[j + 1]; ++k)
        dense_positions.push_back(pattern.row_indices[k] + j * n);
    matrix = SUNSparseMatrix(n, n, pattern.nonzeros(), CSC_MAT, ctx);
    require(matrix != nullptr, "SUNSparseMatrix failed");
    linear_solver = SUNLinSol_KLU(y, matrix, ctx);
    require(linear_solver != nullptr, "SUNLinSol_KLU failed");
    SYMPATHY_CHECK(CVodeSetLinearSolver(mem, linear_solver, matrix));
    SYMPATHY_CHECK(CVodeSetJacFn(mem, CvodesCallbacks::sparse_jacobian));
  } else if (options.linear_solver == LinearSolver::Structured) {
    if (options.derivatives != Derivatives::Model)
      throw std::invalid_argument(
          "the structured linear solver needs the system's own Jacobian, not difference "
          "quotients");
    auto structure = system.low_rank_structure();
    if (!structure)
      throw std::invalid_argument(
          "the structured linear solver needs a Jacobian of the form S + U W^T "
          "(OdeSystem::low_rank_jacobian), which this system does not provide; use the dense "
          "or KLU linear solver");
    if (structure->dimension != n)
      throw std::invalid_argument("the system's low-rank Jacobian structure is not n x n");
    structured = std::make_unique<StructuredSolver>(&call, *structure);
    matrix = new_low_rank_matrix(*structure, ctx);
    require(matrix != nullptr, "SUNMatNewEmpty failed");
    linear_solver = SUNLinSolNewEmpty(ctx);
    require(linear_solver != nullptr, "SUNLinSolNewEmpty failed");
    linear_solver->content = structured.get();
    linear_solver->ops->gettype = structured_type;
    linear_solver->ops->getid = structured_id;
    linear_solver->ops->initialize = structured_initialize;
    linear_solver->ops->setup = CvodesCallbacks::structured_setup;
    linear_solver->ops->solve = CvodesCallbacks::structured_solve;
    linear_solver->ops->free = structured_free;
    SYMPATHY_CHECK(CVodeSetLinearSolver(mem, linear_solver, matrix));
    SYMPATHY_CHECK(CVodeSetJacFn(mem, CvodesCallbacks::low_rank_jacobian));
  } else {
    matrix = SUNDenseMatrix(n, n, ctx);
    require(matrix != nullptr, "SUNDenseMatrix failed");
    linear_solver = SUNLinSol_Dense(y, matrix, ctx);
    require(linear_solver != nullptr, "SUNLinSol_Dense failed");
    SYMPATHY_CHECK(CVodeSetLinearSolver(mem, linear_solver, matrix));
    // Without derivatives CVODES falls back to difference quotients.
    if (system.differentiable() && options.derivatives == Derivatives::Model)
      SYMPATHY_CHECK(CVodeSetJacFn(mem, CvodesCallbacks::dense_jacobian));
  }
}

CvodesStepper::~CvodesStepper() {
  release();
}

// Frees every SUNDIALS object made, in reverse order of creation; once: from the destructor, or
// from a constructor that failed.
void CvodesStepper::release() {
  if (mem) CVodeFree(&mem);
  if (sens_nonlinear_solver) SUNNonlinSolFree(sens_nonlinear_solver);
  if (nonlinear_solver) SUNNonlinSolFree(nonlinear_solver);
  if (linear_solver) SUNLinSolFree(linear_solver);
  if (matrix) SUNMatDestroy(matrix);
  if (out_sens) N_VDestroyVectorArray(out_sens, sens_columns);
  if (yS) N_VDestroyVectorArray(yS, sens_columns);
  if (out) N_VDestroy(out);
  if (y) N_VDestroy(y);
  if (ctx) SUNContext_Free(&ctx);
}

void CvodesStepper::start(double t0, const double* z0, const Eigen::MatrixXd& seeds) {
  const int n = call.system.dimension();
  t_now = t0;
  std::copy(z0, z0 + n, N_VGetArrayPointer(y));
  SYMPATHY_CHECK(CVodeReInit(mem, t0, y));
  const int roots = call.system.switching_count();
  if (roots != root_count) {
    SYMPATHY_CHECK(CVodeRootInit(mem, roots, roots > 0 ? CvodesCallbacks::roots : nullptr));
    if (roots > 0) SYMPATHY_CHECK(CVodeSetNoInactiveRootWarn(mem));
    root_count = roots;
  }
  if (roots > 0 && !call.root_directions.empty())
    SYMPATHY_CHECK(CVodeSetRootDirection(mem, call.root_directions.data()));
  if (call.columns > 0) {
    start_sensitivities(seeds);
  } else if (sens_on) {
    SYMPATHY_CHECK(CVodeSensToggleOff(mem));
    sens_on = false;
  }
}

void CvodesStepper::start_sensitivities(const Eigen::MatrixXd& seeds) {
  const int n = call.system.dimension();
  const int columns = call.columns;
  const int ism =
      options.corrector == SensitivityCorrector::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS;
  if (sens_columns != columns) {
    if (sens_columns > 0) {
      CVodeSensFree(mem);
      sens_initialized = false;
      sens_on = false;
      N_VDestroyVectorArray(yS, sens_columns);
      yS = nullptr;
      N_VDestroyVectorArray(out_sens, sens_columns);
      out_sens = nullptr;
      if (sens_nonlinear_solver) SUNNonlinSolFree(sens_nonlinear_solver);
      sens_nonlinear_solver = nullptr;
    }
    yS = N_VCloneVectorArray(columns, y);
    require(yS != nullptr, "N_VCloneVectorArray failed");
    out_sens = N_VCloneVectorArray(columns, y);
    require(out_sens != nullptr, "N_VCloneVectorArray failed");
    sens_columns = columns;
    columns_in.resize(columns);
    columns_out.resize(columns);
  }
  for (int j = 0; j < columns; ++j)
    std::copy(seeds.col(j).data(), seeds.col(j).data() + n, N_VGetArrayPointer(yS[j]));
  if (!sens_initialized) {
    const bool quotients = options.derivatives == Derivatives::DifferenceQuotients;
    SYMPATHY_CHECK(CVodeSensInit(mem, columns, ism,
                                 quotients ? nullptr : CvodesCallbacks::sensitivity_rhs, yS));
    if (quotients) {
      // CVODES perturbs a parameter array along with the state; dummies that f never reads
      // make the parameter terms zero: initial-state sensitivities alone.
      dq_parameters.assign(columns, 1.0);
      dq_scales.assign(columns, 1.0);
      dq_list.resize(columns);
      for (int j = 0; j < columns; ++j) dq_list[j] = j;
      SYMPATHY_CHECK(
          CVodeSetSensParams(mem, dq_parameters.data(), dq_scales.data(), dq_list.data()));
      SYMPATHY_CHECK(CVodeSetSensDQMethod(mem, CV_CENTERED, 0.0));
    }
    std::vector<double> atols(columns, options.atol);
    SYMPATHY_CHECK(CVodeSensSStolerances(mem, options.rtol, atols.data()));
    SYMPATHY_CHECK(CVodeSetSensErrCon(mem, SUNTRUE));
    if (options.nonlinear_solver == NonlinearSolver::FixedPoint) {
      sens_nonlinear_solver = ism == CV_SIMULTANEOUS
                                  ? SUNNonlinSol_FixedPointSens(columns + 1, y, 0, ctx)
                                  : SUNNonlinSol_FixedPointSens(columns, y, 0, ctx);
      require(sens_nonlinear_solver != nullptr, "SUNNonlinSol_FixedPointSens failed");
      if (ism == CV_SIMULTANEOUS)
        SYMPATHY_CHECK(CVodeSetNonlinearSolverSensSim(mem, sens_nonlinear_solver));
      else
        SYMPATHY_CHECK(CVodeSetNonlinearSolverSensStg(mem, sens_nonlinear_solver));
    }
    sens_initialized = true;
  } else {
    SYMPATHY_CHECK(CVodeSensReInit(mem, ism, yS));
  }
  sens_on = true;
}

void CvodesStepper::restart(double t) {
  t_now = t;
  // Sensitivity columns cross a surface only in a HybridSystem's flow, which restarts with
  // restart_from (the columns mapped by the saltation matrix).
  SYMPATHY_CHECK(CVodeReInit(mem, t, y));
}

void CvodesStepper::restart_from(double t, const double* z, const Eigen::MatrixXd& S) {
  const int n = call.system.dimension();
  std::copy(z, z + n, N_VGetArrayPointer(y));
  restart(t);
  if (!sens_on) return;
  for (int j = 0; j < call.columns; ++j)
    std::copy(S.col(j).data(), S.col(j).data() + n, N_VGetArrayPointer(yS[j]));
  const int ism =
      options.corrector == SensitivityCorrector::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS;
  SYMPATHY_CHECK(CVodeSensReInit(mem, ism, yS));
}

void CvodesStepper::set_max_step(double hmax) {
  SYMPATHY_CHECK(CVodeSetMaxStep(mem, hmax));
}

std::optional<PlannedStep> CvodesStepper::planned_step() {
  long steps = 0;
  SYMPATHY_CHECK(CVodeGetNumSteps(mem, &steps));
  if (steps == 0) return std::nullopt;
  PlannedStep p;
  SYMPATHY_CHECK(CVodeGetCurrentStep(mem, &p.h));
  SYMPATHY_CHECK(CVodeGetCurrentTime(mem, &p.t));
  return p;
}

void CvodesStepper::set_stop_time(double t) {
  SYMPATHY_CHECK(CVodeSetStopTime(mem, t));
}

StepOutcome CvodesStepper::step(double t_end, double& t) {
  call.nonfinite.clear();
  const int flag = CVode(mem, t_end, y, &t, CV_ONE_STEP);
  t_now = t;
  if (flag < 0 || call.callback_error) fail(flag, "CVode");
  if (flag == CV_ROOT_RETURN) return StepOutcome::Root;
  if (flag == CV_TSTOP_RETURN) return StepOutcome::StopTime;
  return StepOutcome::Step;
}

void CvodesStepper::sensitivities(Eigen::MatrixXd& S) {
  const int n = call.system.dimension();
  S.resize(n, call.columns);
  if (call.columns == 0) return;
  double t_sens = 0.0;
  SYMPATHY_CHECK(CVodeGetSens(mem, &t_sens, yS));
  for (int j = 0; j < call.columns; ++j)
    S.col(j) = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(yS[j]), n);
}

void CvodesStepper::interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) {
  const int n = call.system.dimension();
  SYMPATHY_CHECK(CVodeGetDky(mem, t, 0, out));
  z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out), n);
  S.resize(n, call.columns);
  if (call.columns == 0) return;
  SYMPATHY_CHECK(CVodeGetSensDky(mem, t, 0, out_sens));
  for (int j = 0; j < call.columns; ++j)
    S.col(j) = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out_sens[j]), n);
}

void CvodesStepper::interpolate_state(double t, Eigen::VectorXd& z) {
  SYMPATHY_CHECK(CVodeGetDky(mem, t, 0, out));
  z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out), call.system.dimension());
}

void CvodesStepper::collect(FlowStatistics& s) {
  long v = 0;
  if (CVodeGetNumSteps(mem, &v) == CV_SUCCESS) s.steps += v;
  if (CVodeGetNumRhsEvals(mem, &v) == CV_SUCCESS) s.rhs_evaluations += v;
  if (CVodeGetNumLinSolvSetups(mem, &v) == CV_SUCCESS) s.linear_setups += v;
  if (CVodeGetNumErrTestFails(mem, &v) == CV_SUCCESS) s.error_test_failures += v;
  if (CVodeGetNumNonlinSolvIters(mem, &v) == CV_SUCCESS) s.nonlinear_iterations += v;
  if (linear_solver && CVodeGetNumJacEvals(mem, &v) == CV_SUCCESS) s.jacobian_evaluations += v;
  if (sens_on && CVodeGetSensNumRhsEvals(mem, &v) == CV_SUCCESS) s.variational_evaluations += v;
}

#undef SYMPATHY_CHECK

}  // namespace

std::unique_ptr<FlowStepper> make_cvodes_stepper(FlowCall& call, const FlowOptions& options) {
  return std::make_unique<CvodesStepper>(call, options);
}

}  // namespace sympathy::detail
