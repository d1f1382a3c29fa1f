// The CVODES wrapper (see flow.hpp). About 850 lines in one file on purpose: the C callbacks, the
// structured linear solver's SUNDIALS operations and the step loop share the private state of one
// integrator (its SUNDIALS objects, bands and stored exception), which a split would have to
// expose in a header of its own for no reader's benefit.
#include "sympathy/core/flow.hpp"

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
#include <cstring>
#include <limits>
#include <sstream>

#include "sympathy/core/low_rank_solver.hpp"

namespace sympathy {

std::string to_string(Method m) {
  return m == Method::BDF ? "BDF" : "Adams";
}
std::string to_string(LinearSolver s) {
  switch (s) {
    case LinearSolver::Automatic:
      return "automatic";
    case LinearSolver::Dense:
      return "dense";
    case LinearSolver::KLU:
      return "KLU";
    case LinearSolver::Structured:
      return "structured";
  }
  return "?";
}

LinearSolver resolved_linear_solver(const OdeSystem& system, const FlowOptions& options) {
  if (options.linear_solver != LinearSolver::Automatic) return options.linear_solver;
  if (options.derivatives != Derivatives::Model) return LinearSolver::Dense;
  const auto structure = system.low_rank_structure();
  return structure && structure->dimension > 2 * (structure->rank() + 3) ? LinearSolver::Structured
                                                                         : LinearSolver::Dense;
}

OptionCheck FlowOptions::validate() const {
  // CVODES itself refuses tolerances near the unit roundoff ("too much accuracy requested").
  if (!(rtol >= 1e-14 && rtol < 1.0)) return OptionProblem{"rtol", "a number in [1e-14, 1)"};
  if (!positive(atol)) return OptionProblem{"atol", "a positive number"};
  if (max_steps < 1) return OptionProblem{"max_steps", "a positive integer"};
  if (!non_negative(max_step))
    return OptionProblem{"max_step", "0 (no limit) or a positive number"};
  if (!(steep_step_fraction > 0.0 && steep_step_fraction < 2.0 / 3.0))
    return OptionProblem{"steep_step_fraction", "a number in (0, 2/3)"};
  return std::nullopt;
}

FlowStatistics& FlowStatistics::operator+=(const FlowStatistics& o) {
  calls += o.calls;
  steps += o.steps;
  rhs_evaluations += o.rhs_evaluations;
  jacobian_evaluations += o.jacobian_evaluations;
  variational_evaluations += o.variational_evaluations;
  linear_setups += o.linear_setups;
  error_test_failures += o.error_test_failures;
  nonlinear_iterations += o.nonlinear_iterations;
  steep_roots += o.steep_roots;
  switchings += o.switchings;
  return *this;
}

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
  Flow* flow;  // for storing a callback's exception
  LowRankSolver solver;
  double inverse_identity = 1.0;
  StructuredSolver(Flow* f, const LowRankJacobian& structure) : flow(f), solver(structure) {}
};

}  // namespace

// Every SUNDIALS object of one integrator, freed in reverse order of creation.
struct Flow::Cvodes {
  SUNContext ctx = nullptr;
  void* mem = nullptr;
  N_Vector y = nullptr;
  SUNMatrix matrix = nullptr;
  SUNLinearSolver linear_solver = nullptr;
  SUNNonlinearSolver nonlinear_solver = nullptr;
  SUNNonlinearSolver sens_nonlinear_solver = nullptr;
  N_Vector* yS = nullptr;
  int sens_columns = 0;           // as allocated by CVodeSensInit
  bool sens_initialized = false;  // CVodeSensInit called for sens_columns
  bool sens_on = false;
  bool initialized = false;

  // Sparse (CSC) pattern of the Jacobian for KLU, and where each entry sits in the dense one.
  std::vector<sunindextype> column_starts, row_indices;
  std::vector<int> dense_positions;
  Eigen::MatrixXd jacobian;
  std::vector<const double*> columns_in;
  std::vector<double*> columns_out;
  std::vector<double> dq_parameters, dq_scales;  // for CVODES's difference quotients
  std::vector<int> dq_list;
  std::unique_ptr<StructuredSolver> structured;  // LinearSolver::Structured; read by linear_solver

  Cvodes() = default;
  Cvodes(const Cvodes&) = delete;
  Cvodes& operator=(const Cvodes&) = delete;
  ~Cvodes() {
    if (mem) CVodeFree(&mem);
    if (sens_nonlinear_solver) SUNNonlinSolFree(sens_nonlinear_solver);
    if (nonlinear_solver) SUNNonlinSolFree(nonlinear_solver);
    if (linear_solver) SUNLinSolFree(linear_solver);
    if (matrix) SUNMatDestroy(matrix);
    if (yS) N_VDestroyVectorArray(yS, sens_columns);
    if (y) N_VDestroy(y);
    if (ctx) SUNContext_Free(&ctx);
  }
};

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
// the Flow).
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
  s->content = nullptr;  // owned by the Flow
  SUNLinSolFreeEmpty(s);
  return SUNLS_SUCCESS;
}

}  // namespace

// C callbacks. They never let a C++ exception cross CVODES: it is stored and rethrown after
// CVode returns.
struct FlowCallbacks {
  static int rhs(sunrealtype t, N_Vector y, N_Vector ydot, void* user) {
    auto* flow = static_cast<Flow*>(user);
    try {
      const int n = flow->system_.dimension();
      double* dz = N_VGetArrayPointer(ydot);
      flow->system_.rhs(t, N_VGetArrayPointer(y), flow->values_.data(), dz);
      for (int i = 0; i < n; ++i)
        if (!std::isfinite(dz[i])) return 1;  // recoverable: CVODES retries a smaller step
      return 0;
    } catch (...) {
      flow->callback_error_ = std::current_exception();
      return -1;
    }
  }

  static int dense_jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac, void* user,
                            N_Vector, N_Vector, N_Vector) {
    auto* flow = static_cast<Flow*>(user);
    try {
      const int n = flow->system_.dimension();
      Eigen::Map<Eigen::MatrixXd> out(SM_DATA_D(jac), n, n);
      flow->system_.jacobian(t, N_VGetArrayPointer(y), flow->values_.data(), flow->cv_->jacobian);
      out = flow->cv_->jacobian;
      return 0;
    } catch (...) {
      flow->callback_error_ = std::current_exception();
      return -1;
    }
  }

  static int sparse_jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac, void* user,
                             N_Vector, N_Vector, N_Vector) {
    auto* flow = static_cast<Flow*>(user);
    try {
      auto& cv = *flow->cv_;
      flow->system_.jacobian(t, N_VGetArrayPointer(y), flow->values_.data(), cv.jacobian);
      std::copy(cv.column_starts.begin(), cv.column_starts.end(), SM_INDEXPTRS_S(jac));
      std::copy(cv.row_indices.begin(), cv.row_indices.end(), SM_INDEXVALS_S(jac));
      double* values = SM_DATA_S(jac);
      const double* dense = cv.jacobian.data();
      for (std::size_t k = 0; k < cv.dense_positions.size(); ++k)
        values[k] = dense[cv.dense_positions[k]];
      return 0;
    } catch (...) {
      flow->callback_error_ = std::current_exception();
      return -1;
    }
  }

  static int sensitivity_rhs(int columns, sunrealtype t, N_Vector y, N_Vector /*ydot*/,
                             N_Vector* yS, N_Vector* ySdot, void* user, N_Vector, N_Vector) {
    auto* flow = static_cast<Flow*>(user);
    try {
      auto& cv = *flow->cv_;
      for (int j = 0; j < columns; ++j) {
        cv.columns_in[j] = N_VGetArrayPointer(yS[j]);
        cv.columns_out[j] = N_VGetArrayPointer(ySdot[j]);
      }
      flow->system_.variational_rhs(t, N_VGetArrayPointer(y), flow->values_.data(), columns,
                                    cv.columns_in.data(), cv.columns_out.data(), flow->parameters_);
      return 0;
    } catch (...) {
      flow->callback_error_ = std::current_exception();
      return -1;
    }
  }

  static int roots(sunrealtype t, N_Vector y, sunrealtype* g, void* user) {
    auto* flow = static_cast<Flow*>(user);
    try {
      flow->system_.switching_functions(t, N_VGetArrayPointer(y), flow->values_.data(), g);
      return 0;
    } catch (...) {
      flow->callback_error_ = std::current_exception();
      return -1;
    }
  }

  // The Jacobian in low-rank form, written into a LowRankMatrix.
  static int low_rank_jacobian(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix jac,
                               void* user, N_Vector, N_Vector, N_Vector) {
    auto* flow = static_cast<Flow*>(user);
    try {
      auto& m = *static_cast<LowRankMatrix*>(jac->content);
      if (!flow->system_.low_rank_jacobian(t, N_VGetArrayPointer(y), flow->values_.data(),
                                           m.jacobian))
        throw std::logic_error("the system stopped providing its low-rank Jacobian");
      m.identity = 0.0;
      m.scale = 1.0;
      return 0;
    } catch (...) {
      flow->callback_error_ = std::current_exception();
      return -1;
    }
  }

  // Factors A = identity * I + scale * J = identity * (I - gamma J); a singular A is a recoverable
  // failure (CVODES retries with a smaller step), as for the dense LU.
  static int structured_setup(SUNLinearSolver s, SUNMatrix a) {
    auto& st = structured(s);
    try {
      const auto& m = low_rank(a);
      if (!(m.identity != 0.0)) return SUNLS_ILL_INPUT;
      st.inverse_identity = 1.0 / m.identity;
      return st.solver.factor(m.jacobian, -m.scale / m.identity) ? SUNLS_SUCCESS
                                                                 : SUNLS_LUFACT_FAIL;
    } catch (...) {
      st.flow->callback_error_ = std::current_exception();
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
  }

  static int structured_solve(SUNLinearSolver s, SUNMatrix, N_Vector x, N_Vector b, sunrealtype) {
    auto& st = structured(s);
    try {
      if (x != b) N_VScale(1.0, b, x);
      st.solver.solve(N_VGetArrayPointer(x));
      if (st.inverse_identity != 1.0) N_VScale(st.inverse_identity, x, x);
      return SUNLS_SUCCESS;
    } catch (...) {
      st.flow->callback_error_ = std::current_exception();
      return SUNLS_PACKAGE_FAIL_UNREC;
    }
  }

  static void error_handler(int /*code*/, const char* module, const char* function, char* msg,
                            void* user) {
    auto* flow = static_cast<Flow*>(user);
    flow->last_error_ = std::string(module) + "/" + function + ": " + msg;
  }
};

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::runtime_error("SUNDIALS: " + what);
}

}  // namespace

void Flow::fail(int flag, const char* function) {
  if (callback_error_) {
    auto e = callback_error_;
    callback_error_ = nullptr;
    std::rethrow_exception(e);
  }
  std::ostringstream msg;
  msg << function << " failed at t = " << t_ << ": " << CVodeGetReturnFlagName(flag);
  if (!last_error_.empty()) msg << " (" << last_error_ << ")";
  last_error_.clear();
  throw IntegrationError(msg.str(), t_);
}

#define SYMPATHY_CHECK(call)           \
  do {                                 \
    const int flag_ = (call);          \
    if (flag_ < 0) fail(flag_, #call); \
  } while (false)

Flow::Flow(const OdeSystem& system, FlowOptions options)
    : system_(system), options_(options), cv_(std::make_unique<Cvodes>()) {
  options_.linear_solver = resolved_linear_solver(system_, options_);
  if (const auto problem = options_.validate())
    throw std::invalid_argument("flow options: " + problem->message());
  const int n = system_.dimension();
  auto& cv = *cv_;
  require(SUNContext_Create(nullptr, &cv.ctx) == 0, "SUNContext_Create failed");
  cv.y = N_VNew_Serial(n, cv.ctx);
  require(cv.y != nullptr, "N_VNew_Serial failed");
  // Fused vector operations (one pass over the memory for a linear combination of several
  // vectors, which the sensitivity columns are): 6-7% less time per step measured on the row
  // setup's branches; clones (the sensitivity columns) inherit them.
  require(N_VEnableFusedOps_Serial(cv.y, SUNTRUE) == 0, "N_VEnableFusedOps_Serial failed");
  N_VConst(0.0, cv.y);
  cv.mem = CVodeCreate(options_.method == Method::BDF ? CV_BDF : CV_ADAMS, cv.ctx);
  require(cv.mem != nullptr, "CVodeCreate failed");
  SYMPATHY_CHECK(CVodeSetErrHandlerFn(cv.mem, FlowCallbacks::error_handler, this));
  SYMPATHY_CHECK(CVodeInit(cv.mem, FlowCallbacks::rhs, 0.0, cv.y));
  SYMPATHY_CHECK(CVodeSetUserData(cv.mem, this));
  SYMPATHY_CHECK(CVodeSStolerances(cv.mem, options_.rtol, options_.atol));
  SYMPATHY_CHECK(CVodeSetMaxNumSteps(cv.mem, options_.max_steps));

  if (options_.nonlinear_solver == NonlinearSolver::FixedPoint) {
    cv.nonlinear_solver = SUNNonlinSol_FixedPoint(cv.y, 0, cv.ctx);
    require(cv.nonlinear_solver != nullptr, "SUNNonlinSol_FixedPoint failed");
    SYMPATHY_CHECK(CVodeSetNonlinearSolver(cv.mem, cv.nonlinear_solver));
  } else {
    cv.nonlinear_solver = SUNNonlinSol_Newton(cv.y, cv.ctx);
    require(cv.nonlinear_solver != nullptr, "SUNNonlinSol_Newton failed");
    SYMPATHY_CHECK(CVodeSetNonlinearSolver(cv.mem, cv.nonlinear_solver));
    if (options_.linear_solver == LinearSolver::KLU) {
      if (!system_.differentiable() || options_.derivatives != Derivatives::Model)
        throw std::invalid_argument("the KLU linear solver needs the system's Jacobian");
      auto entries = system_.jacobian_pattern();
      if (entries.empty())
        for (int j = 0; j < n; ++j)
          for (int i = 0; i < n; ++i) entries.emplace_back(i, j);
      // Compressed sparse columns, entries checked and repeats merged (a sparse part of rank 0).
      const LowRankJacobian pattern(n, 0, std::move(entries));
      cv.column_starts.assign(pattern.column_starts.begin(), pattern.column_starts.end());
      cv.row_indices.assign(pattern.row_indices.begin(), pattern.row_indices.end());
      for (int j = 0; j < n; ++j)
        for (int k = pattern.column_starts[j]; k < pattern.column_starts[j + 1]; ++k)
          cv.dense_positions.push_back(pattern.row_indices[k] + j * n);
      cv.matrix = SUNSparseMatrix(n, n, pattern.nonzeros(), CSC_MAT, cv.ctx);
      require(cv.matrix != nullptr, "SUNSparseMatrix failed");
      cv.linear_solver = SUNLinSol_KLU(cv.y, cv.matrix, cv.ctx);
      require(cv.linear_solver != nullptr, "SUNLinSol_KLU failed");
      SYMPATHY_CHECK(CVodeSetLinearSolver(cv.mem, cv.linear_solver, cv.matrix));
      SYMPATHY_CHECK(CVodeSetJacFn(cv.mem, FlowCallbacks::sparse_jacobian));
    } else if (options_.linear_solver == LinearSolver::Structured) {
      if (options_.derivatives != Derivatives::Model)
        throw std::invalid_argument(
            "the structured linear solver needs the system's own Jacobian, not difference "
            "quotients");
      auto structure = system_.low_rank_structure();
      if (!structure)
        throw std::invalid_argument(
            "the structured linear solver needs a Jacobian of the form S + U W^T "
            "(OdeSystem::low_rank_jacobian), which this system does not provide; use the dense "
            "or KLU linear solver");
      if (structure->dimension != n)
        throw std::invalid_argument("the system's low-rank Jacobian structure is not n x n");
      cv.structured = std::make_unique<StructuredSolver>(this, *structure);
      cv.matrix = new_low_rank_matrix(*structure, cv.ctx);
      require(cv.matrix != nullptr, "SUNMatNewEmpty failed");
      cv.linear_solver = SUNLinSolNewEmpty(cv.ctx);
      require(cv.linear_solver != nullptr, "SUNLinSolNewEmpty failed");
      cv.linear_solver->content = cv.structured.get();
      cv.linear_solver->ops->gettype = structured_type;
      cv.linear_solver->ops->getid = structured_id;
      cv.linear_solver->ops->initialize = structured_initialize;
      cv.linear_solver->ops->setup = FlowCallbacks::structured_setup;
      cv.linear_solver->ops->solve = FlowCallbacks::structured_solve;
      cv.linear_solver->ops->free = structured_free;
      SYMPATHY_CHECK(CVodeSetLinearSolver(cv.mem, cv.linear_solver, cv.matrix));
      SYMPATHY_CHECK(CVodeSetJacFn(cv.mem, FlowCallbacks::low_rank_jacobian));
    } else {
      cv.matrix = SUNDenseMatrix(n, n, cv.ctx);
      require(cv.matrix != nullptr, "SUNDenseMatrix failed");
      cv.linear_solver = SUNLinSol_Dense(cv.y, cv.matrix, cv.ctx);
      require(cv.linear_solver != nullptr, "SUNLinSol_Dense failed");
      SYMPATHY_CHECK(CVodeSetLinearSolver(cv.mem, cv.linear_solver, cv.matrix));
      // Without derivatives CVODES falls back to difference quotients.
      if (system_.differentiable() && options_.derivatives == Derivatives::Model)
        SYMPATHY_CHECK(CVodeSetJacFn(cv.mem, FlowCallbacks::dense_jacobian));
    }
  }

  // Steep zones and switching surfaces are set up by each call (start), from its parameter values.
  dz_scratch_.resize(n);
  cv.initialized = true;
}

Flow::~Flow() = default;

// Zones and switching surfaces follow the call's parameter values (a zone's width may depend on
// them).
void Flow::configure_roots() {
  const int n = system_.dimension();
  zones_ =
      options_.resolve_steep_zones ? system_.steep_zones(values_.data()) : std::vector<SteepZone>{};
  levels_.clear();
  for (const auto& zone : zones_) {
    if (zone.component < 0 || zone.component >= n || !(zone.width > 0.0) ||
        !(zone.scale > zone.width))
      throw std::invalid_argument("invalid steep zone of the system");
    std::vector<double> levels{zone.scale};
    while (levels.back() >= zone.width) levels.push_back(levels.back() / 3.0);
    levels_.push_back(std::move(levels));
  }
  switching_count_ = system_.switching_count();
  if (switching_count_ != static_cast<int>(root_info_.size())) {
    SYMPATHY_CHECK(CVodeRootInit(cv_->mem, switching_count_,
                                 switching_count_ > 0 ? FlowCallbacks::roots : nullptr));
    if (switching_count_ > 0) SYMPATHY_CHECK(CVodeSetNoInactiveRootWarn(cv_->mem));
    root_info_.assign(switching_count_, 0);
  }
}

void Flow::start(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                 std::span<const int> initial_components, std::span<const int> parameters) {
  const int n = system_.dimension();
  const int sensitivity_columns = static_cast<int>(initial_components.size() + parameters.size());
  for (int c : initial_components)
    if (c < 0 || c >= n)
      throw std::invalid_argument("flow: no state component " + std::to_string(c));
  for (int k : parameters)
    if (k < 0 || k >= system_.parameter_count())
      throw std::invalid_argument("flow: no parameter with index " + std::to_string(k));
  system_.check_parameters(p);
  if (z0.size() != n)
    throw std::invalid_argument("initial state has " + std::to_string(z0.size()) +
                                " entries; the system has " + std::to_string(n));
  if (!z0.allFinite()) throw std::invalid_argument("initial state is not finite");
  auto& cv = *cv_;
  t_ = t0;
  callback_error_ = nullptr;
  last_error_.clear();
  values_ = p;
  std::copy(z0.data(), z0.data() + n, N_VGetArrayPointer(cv.y));
  SYMPATHY_CHECK(CVodeReInit(cv.mem, t0, cv.y));
  configure_roots();

  parameters_.assign(parameters.begin(), parameters.end());
  if (sensitivity_columns > 0) {
    if (!system_.differentiable())
      throw std::invalid_argument("sensitivities need a differentiable system");
    if (options_.derivatives == Derivatives::DifferenceQuotients && !parameters.empty())
      throw std::invalid_argument(
          "parameter sensitivities need the system's derivatives, not difference quotients");
    const int ism =
        options_.corrector == SensitivityCorrector::Staggered ? CV_STAGGERED : CV_SIMULTANEOUS;
    if (cv.sens_columns != sensitivity_columns) {
      if (cv.sens_columns > 0) {
        CVodeSensFree(cv.mem);
        cv.sens_initialized = false;
        cv.sens_on = false;
        N_VDestroyVectorArray(cv.yS, cv.sens_columns);
        cv.yS = nullptr;
        if (cv.sens_nonlinear_solver) SUNNonlinSolFree(cv.sens_nonlinear_solver);
        cv.sens_nonlinear_solver = nullptr;
      }
      cv.yS = N_VCloneVectorArray(sensitivity_columns, cv.y);
      require(cv.yS != nullptr, "N_VCloneVectorArray failed");
      cv.sens_columns = sensitivity_columns;
      cv.columns_in.resize(sensitivity_columns);
      cv.columns_out.resize(sensitivity_columns);
    }
    // Initial sensitivities: unit vectors in the state columns, zero in the parameter columns.
    const int state_columns = static_cast<int>(initial_components.size());
    for (int j = 0; j < sensitivity_columns; ++j) {
      N_VConst(0.0, cv.yS[j]);
      if (j < state_columns) N_VGetArrayPointer(cv.yS[j])[initial_components[j]] = 1.0;
    }
    if (!cv.sens_initialized) {
      const bool quotients = options_.derivatives == Derivatives::DifferenceQuotients;
      SYMPATHY_CHECK(CVodeSensInit(cv.mem, sensitivity_columns, ism,
                                   quotients ? nullptr : FlowCallbacks::sensitivity_rhs, cv.yS));
      if (quotients) {
        // CVODES perturbs a parameter array along with the state; dummies that f never reads
        // make the parameter terms zero: initial-state sensitivities alone.
        cv.dq_parameters.assign(sensitivity_columns, 1.0);
        cv.dq_scales.assign(sensitivity_columns, 1.0);
        cv.dq_list.resize(sensitivity_columns);
        for (int j = 0; j < sensitivity_columns; ++j) cv.dq_list[j] = j;
        SYMPATHY_CHECK(CVodeSetSensParams(cv.mem, cv.dq_parameters.data(), cv.dq_scales.data(),
                                          cv.dq_list.data()));
        SYMPATHY_CHECK(CVodeSetSensDQMethod(cv.mem, CV_CENTERED, 0.0));
      }
      std::vector<double> atols(sensitivity_columns, options_.atol);
      SYMPATHY_CHECK(CVodeSensSStolerances(cv.mem, options_.rtol, atols.data()));
      SYMPATHY_CHECK(CVodeSetSensErrCon(cv.mem, SUNTRUE));
      if (options_.nonlinear_solver == NonlinearSolver::FixedPoint) {
        cv.sens_nonlinear_solver =
            ism == CV_SIMULTANEOUS
                ? SUNNonlinSol_FixedPointSens(sensitivity_columns + 1, cv.y, 0, cv.ctx)
                : SUNNonlinSol_FixedPointSens(sensitivity_columns, cv.y, 0, cv.ctx);
        require(cv.sens_nonlinear_solver != nullptr, "SUNNonlinSol_FixedPointSens failed");
        if (ism == CV_SIMULTANEOUS)
          SYMPATHY_CHECK(CVodeSetNonlinearSolverSensSim(cv.mem, cv.sens_nonlinear_solver));
        else
          SYMPATHY_CHECK(CVodeSetNonlinearSolverSensStg(cv.mem, cv.sens_nonlinear_solver));
      }
      cv.sens_initialized = true;
    } else {
      SYMPATHY_CHECK(CVodeSensReInit(cv.mem, ism, cv.yS));
    }
    cv.sens_on = true;
  } else if (cv.sens_on) {
    SYMPATHY_CHECK(CVodeSensToggleOff(cv.mem));
    cv.sens_on = false;
  }
  forced_stop_.reset();
  bands_.assign(zones_.size(), -2);  // unknown: set from the state below
  update_bands(t0);
  ++statistics_.calls;
}

// The band of a zone is the innermost level l with |z_c| < v_l (-1 outside all levels). The
// step is capped at fraction * v_(l+1) / |dz_c/dt|: a step that crosses v_(l+1) then lands
// above v_(l+2) (fraction < 2/3), so no level is ever jumped, and the innermost band, the
// steep part itself, is crossed in several steps.
void Flow::update_max_step(double t) {
  double hmax = options_.max_step > 0.0 ? options_.max_step : 0.0;
  if (!zones_.empty()) {
    const double* z = N_VGetArrayPointer(cv_->y);
    system_.rhs(t, z, values_.data(), dz_scratch_.data());
    ++statistics_.rhs_evaluations;
    for (std::size_t i = 0; i < zones_.size(); ++i) {
      const double rate = std::abs(dz_scratch_[zones_[i].component]);
      if (rate == 0.0) continue;
      const auto& levels = levels_[i];
      const int last = static_cast<int>(levels.size()) - 1;
      const double inner = levels[std::min(bands_[i] + 1, last)];
      const double cap = options_.steep_step_fraction * inner / rate;
      hmax = hmax > 0.0 ? std::min(hmax, cap) : cap;
    }
  }
  SYMPATHY_CHECK(CVodeSetMaxStep(cv_->mem, hmax));
  // CVODES applies a new maximum only when it next changes the step size; a step it keeps
  // unchanged may exceed it. Shrink the step already planned with a stop time one cap ahead.
  forced_stop_.reset();
  long steps = 0;
  SYMPATHY_CHECK(CVodeGetNumSteps(cv_->mem, &steps));
  if (hmax > 0.0 && steps > 0) {
    double h_next = 0.0, t_internal = 0.0;
    SYMPATHY_CHECK(CVodeGetCurrentStep(cv_->mem, &h_next));
    SYMPATHY_CHECK(CVodeGetCurrentTime(cv_->mem, &t_internal));
    if (h_next > hmax) forced_stop_ = t_internal + hmax;
  }
}

// A state on a level counts as inside it.
int Flow::band_of(std::size_t zone, double value) const {
  int band = -1;
  const auto& levels = levels_[zone];
  for (int l = 0; l < static_cast<int>(levels.size()); ++l)
    if (std::abs(value) <= levels[l]) band = l;
  return band;
}

void Flow::update_bands(double t) {
  const double* z = N_VGetArrayPointer(cv_->y);
  bool changed = false;
  for (std::size_t i = 0; i < zones_.size(); ++i) {
    const int band = band_of(i, z[zones_[i].component]);
    if (band != bands_[i]) {
      if (bands_[i] != -2) ++statistics_.steep_roots;
      bands_[i] = band;
      changed = true;
    }
  }
  if (changed || bands_.empty()) update_max_step(t);
}

void Flow::on_switching() {
  auto& cv = *cv_;
  SYMPATHY_CHECK(CVodeGetRootInfo(cv.mem, root_info_.data()));
  // f jumps here: restart the multistep method from the state at the surface.
  ++statistics_.switchings;
  collect_statistics();
  SYMPATHY_CHECK(CVodeReInit(cv.mem, t_, cv.y));
  forced_stop_.reset();
  update_max_step(t_);
}

// One internal step at a time: after each, the steep zones' bands are read off the state, and a
// changed band sets the step cap at once. `after_step(t_old, t_new)` may interpolate outputs in
// the step just taken (CVodeGetDky) before anything restarts the integrator; true stops there.
void Flow::integrate_to(double t_end, const std::function<bool(double, double)>& after_step) {
  // A failed call's work counts too (the caller collects only after a success).
  try {
    step_to(t_end, after_step);
  } catch (const IntegrationError&) {
    collect_statistics();
    throw;
  }
}

void Flow::step_to(double t_end, const std::function<bool(double, double)>& after_step) {
  auto& cv = *cv_;
  // One step per CVode call, so CVODES's own step limit never triggers: count here.
  for (long steps = 0; t_ < t_end; ++steps) {
    if (steps >= options_.max_steps) {
      std::ostringstream msg;
      msg << "CVode: more than " << options_.max_steps << " steps before t = " << t_end
          << ", at t = " << t_;
      throw IntegrationError(msg.str(), t_);
    }
    const bool forced = forced_stop_ && *forced_stop_ < t_end;
    SYMPATHY_CHECK(CVodeSetStopTime(cv.mem, forced ? *forced_stop_ : t_end));
    const double t_old = t_;
    const int flag = CVode(cv.mem, t_end, cv.y, &t_, CV_ONE_STEP);
    if (flag < 0 || callback_error_) fail(flag, "CVode");
    if (after_step && after_step(t_old, t_)) return;
    if (flag == CV_ROOT_RETURN) {
      on_switching();
      continue;
    }
    if (flag == CV_TSTOP_RETURN && forced) forced_stop_.reset();  // the shortened step is done
    if (!zones_.empty()) update_bands(t_);
  }
}

void Flow::collect_statistics() {
  auto& cv = *cv_;
  long v = 0;
  if (CVodeGetNumSteps(cv.mem, &v) == CV_SUCCESS) statistics_.steps += v;
  if (CVodeGetNumRhsEvals(cv.mem, &v) == CV_SUCCESS) statistics_.rhs_evaluations += v;
  if (CVodeGetNumLinSolvSetups(cv.mem, &v) == CV_SUCCESS) statistics_.linear_setups += v;
  if (CVodeGetNumErrTestFails(cv.mem, &v) == CV_SUCCESS) statistics_.error_test_failures += v;
  if (CVodeGetNumNonlinSolvIters(cv.mem, &v) == CV_SUCCESS) statistics_.nonlinear_iterations += v;
  if (cv.linear_solver && CVodeGetNumJacEvals(cv.mem, &v) == CV_SUCCESS)
    statistics_.jacobian_evaluations += v;
  if (cv.sens_on && CVodeGetSensNumRhsEvals(cv.mem, &v) == CV_SUCCESS)
    statistics_.variational_evaluations += v;
}

Eigen::VectorXd Flow::advance(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                              double t1) {
  if (!(t1 >= t0)) throw std::invalid_argument("flow: end time before start time");
  start(z0, p, t0, {}, {});
  integrate_to(t1);
  collect_statistics();
  const int n = system_.dimension();
  return Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(cv_->y), n);
}

void Flow::sample(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                  std::span<const double> times,
                  const std::function<void(double, const Eigen::VectorXd&)>& observer) {
  sample_until(z0, p, t0, times, [&](double t, const Eigen::VectorXd& z) {
    observer(t, z);
    return false;
  });
}

bool Flow::sample_until(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                        std::span<const double> times,
                        const std::function<bool(double, const Eigen::VectorXd&)>& done) {
  return sample_run(
      z0, p, t0, times, {}, {},
      [&](double t, const Eigen::VectorXd& z, const Eigen::MatrixXd&) { return done(t, z); });
}

FlowDerivatives Flow::advance_with_sensitivities(const Eigen::VectorXd& z0,
                                                 const ParameterValues& p, double t0, double t1,
                                                 bool state, std::span<const int> parameters) {
  if (!(t1 >= t0)) throw std::invalid_argument("flow: end time before start time");
  const int n = system_.dimension();
  const int state_columns = state ? n : 0;
  const int columns = state_columns + static_cast<int>(parameters.size());
  if (columns == 0) {
    FlowDerivatives r;
    r.state = advance(z0, p, t0, t1);
    return r;
  }
  std::vector<int> components(state_columns);
  for (int j = 0; j < state_columns; ++j) components[j] = j;
  start(z0, p, t0, components, parameters);
  integrate_to(t1);
  collect_statistics();

  auto& cv = *cv_;
  FlowDerivatives r;
  r.state = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(cv.y), n);
  double t_sens = 0.0;
  SYMPATHY_CHECK(CVodeGetSens(cv.mem, &t_sens, cv.yS));
  r.transition.resize(state_columns, state_columns);
  for (int j = 0; j < state_columns; ++j)
    r.transition.col(j) = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(cv.yS[j]), n);
  r.parameter_sensitivities.resize(n, static_cast<int>(parameters.size()));
  for (int k = 0; k < static_cast<int>(parameters.size()); ++k)
    r.parameter_sensitivities.col(k) =
        Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(cv.yS[state_columns + k]), n);
  return r;
}

void Flow::sample_with_sensitivities(
    const Eigen::VectorXd& z0, const ParameterValues& p, double t0, std::span<const double> times,
    std::span<const int> initial_components, std::span<const int> parameters,
    const std::function<void(double, const Eigen::VectorXd&, const Eigen::MatrixXd&)>& observer) {
  sample_run(z0, p, t0, times, initial_components, parameters,
             [&](double t, const Eigen::VectorXd& z, const Eigen::MatrixXd& S) {
               observer(t, z, S);
               return false;
             });
}

// Outputs at t0 itself (the seeds), then those inside each step, from the step's interpolant.
bool Flow::sample_run(
    const Eigen::VectorXd& z0, const ParameterValues& p, double t0, std::span<const double> times,
    std::span<const int> initial_components, std::span<const int> parameters,
    const std::function<bool(double, const Eigen::VectorXd&, const Eigen::MatrixXd&)>& observer) {
  if (times.empty()) return false;
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!(times[i] >= (i == 0 ? t0 : times[i - 1])))
      throw std::invalid_argument("flow: sample times must be increasing and not before t0");
  const int n = system_.dimension();
  const int columns = static_cast<int>(initial_components.size() + parameters.size());
  start(z0, p, t0, initial_components, parameters);
  auto& cv = *cv_;
  Eigen::VectorXd z(n);
  Eigen::MatrixXd S(n, columns);
  std::size_t next = 0;
  while (next < times.size() && times[next] <= t0) {
    z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(cv.y), n);
    for (int j = 0; j < columns; ++j)
      S.col(j) = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(cv.yS[j]), n);
    if (observer(times[next++], z, S)) return true;
  }
  // Scratch vectors for the interpolated outputs, freed however the run ends.
  const std::unique_ptr<std::remove_pointer_t<N_Vector>, void (*)(N_Vector)> out(N_VClone(cv.y),
                                                                                 N_VDestroy);
  const auto destroy_array = [columns](N_Vector* v) {
    if (v) N_VDestroyVectorArray(v, columns);
  };
  const std::unique_ptr<N_Vector, decltype(destroy_array)> out_sens(
      columns > 0 ? N_VCloneVectorArray(columns, cv.y) : nullptr, destroy_array);
  require(out != nullptr && (columns == 0 || out_sens != nullptr), "N_VClone failed");
  bool stopped = false;
  integrate_to(times.back(), [&](double, double t_new) {
    while (!stopped && next < times.size() && times[next] <= t_new) {
      SYMPATHY_CHECK(CVodeGetDky(cv.mem, times[next], 0, out.get()));
      if (columns > 0) SYMPATHY_CHECK(CVodeGetSensDky(cv.mem, times[next], 0, out_sens.get()));
      z = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out.get()), n);
      for (int j = 0; j < columns; ++j)
        S.col(j) = Eigen::Map<const Eigen::VectorXd>(N_VGetArrayPointer(out_sens.get()[j]), n);
      stopped = observer(times[next++], z, S);
    }
    return stopped;
  });
  collect_statistics();
  return stopped;
}

}  // namespace sympathy
