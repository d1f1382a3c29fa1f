// Least-squares fit of an OdeSystem's parameters (and, optionally, of initial state components)
// to a recorded trajectory: samples of some state components at increasing times.
//
// The residuals are (z_c(t_i) - data_ik) / scale_k over every sample i and observed column k,
// with z(t) integrated from the initial state at the first sample time. Samples at that time of
// components whose initial value is fixed are left out: they do not depend on any unknown. One
// evaluation integrates the trajectory once; with the Jacobian it carries the flow's forward
// sensitivities for the free initial components and the free parameters, interpolated at the
// sample times (Flow::sample_with_sensitivities).
//
// Unknowns are scaled: a positive parameter as log(p / p_start), so that parameters spanning
// orders of magnitude (a damping of 2.4e-6 beside a stiffness of 14.7) are equally weighted and
// stay positive; a parameter of either sign and an initial component as (v - v_start) / scale.
//
// Stages: an optional global stage over a box (an NLopt global algorithm, derivative-free on
// plain simulations, or multi-start MLSL), then a local stage from the best point found:
// Levenberg-Marquardt on the residuals with the Jacobian J (default), or an NLopt algorithm on
// the sum of squares with its analytic gradient 2 J^T r (SLSQP, L-BFGS, MMA) or without (BOBYQA,
// Nelder-Mead); a local NLopt stage ends with Gauss-Newton (Levenberg-Marquardt) steps that
// polish the optimum and give the Jacobian there. Levenberg-Marquardt is the default because it
// uses J^T J, which the other methods must learn from gradients: on a metronome's d and s it
// needs 8 integrations where SLSQP needs 59 and L-BFGS 49 (README, "Fitting parameters").
// Standard errors come from the Gauss-Newton covariance at the optimum: s^2 (J^T J)^-1 with
// s^2 = RSS / (N - p), N residuals and p unknowns, in physical units.
#pragma once

#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/flow.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

struct FreeParameter {
  int index = 0;  // a named parameter; its value in TrajectoryFitProblem::parameters starts it
  // Positive parameters are fitted as log(p / p_start) (bounds are then > 0 automatically);
  // others as (p - p_start) / scale.
  bool logarithmic = true;
  double scale = 1.0;
  double lower = 0.0;  // physical bounds, kept throughout
  double upper = kInfinity;
  double search_lower = 0.0;  // the box of the global stage (finite, inside the bounds)
  double search_upper = 0.0;
};

struct FreeInitial {
  int component = 0;  // its starting value is TrajectoryFitProblem::initial_state[component]
  double scale = 1.0;
  double search_lower = 0.0;  // the box of the global stage
  double search_upper = 0.0;
};

struct TrajectoryFitProblem {
  std::vector<double> times;         // strictly increasing; the integration starts at times[0]
  std::vector<int> observed;         // the observed state components, one per column of `values`
  Eigen::MatrixXd values;            // samples x observed
  Eigen::VectorXd column_scale;      // residual weights 1/scale_k per column (empty: all 1)
  Eigen::VectorXd initial_state;     // at times[0]; free components start here
  ParameterValues parameter_values;  // the system's values; free parameters start here
  std::vector<FreeParameter> parameters;
  std::vector<FreeInitial> initial;
};

enum class LocalMethod { Slsqp, Lbfgs, Mma, Bobyqa, NelderMead, LevenbergMarquardt };
enum class GlobalMethod { None, ControlledRandomSearch, Direct, Isres, Mlsl };
std::string to_string(LocalMethod m);
std::string to_string(GlobalMethod m);

struct TrajectoryFitOptions {
  FlowOptions flow = [] {
    FlowOptions o;
    o.rtol = 1e-9;
    o.atol = 1e-11;
    return o;
  }();
  LocalMethod local = LocalMethod::LevenbergMarquardt;
  bool polish = true;  // Gauss-Newton steps after a local NLopt stage
  GlobalMethod global = GlobalMethod::None;
  int global_evaluations = 400;
  unsigned seed = 1;             // NLopt's random numbers, for reproducible global stages
  int max_evaluations = 200;     // of the local stage and of the polish, each
  double step_tolerance = 1e-9;  // on the scaled unknowns
  double rss_tolerance = 1e-10;  // relative change, and relative predicted decrease
  // Statistical convergence: the Gauss-Newton step left is below this many standard errors
  // (its length in the metric of the covariance, Bates and Watts' relative offset).
  double offset_tolerance = 1e-3;
  double rank_tolerance = 1e-8;  // relative singular value below which a direction is lost
  // Asked before each integration (may be empty): true ends the fit at the best point so far,
  // with its statistics there, not converged, stop reason "interrupted" (Python's Ctrl-C).
  std::function<bool()> stop_requested;
};

// One stage of the fit: what ran, how long, what it achieved and why it stopped.
struct FitStage {
  std::string name;    // "global", "local", "polish"
  std::string method;  // e.g. "NLopt SLSQP"
  int evaluations = 0;
  double rss_start = 0.0;
  double rss_end = 0.0;
  std::string stop_reason;
  double seconds = 0.0;
};

struct TrajectoryFitResult {
  bool interrupted = false;  // ended by options.stop_requested
  Eigen::VectorXd start;     // unknowns in physical units: the free parameters, then the free
  Eigen::VectorXd values;    // initial components; at the start and fitted
  ParameterValues fitted_parameters;  // the problem's parameter values with the fitted ones set
  Eigen::VectorXd errors;  // standard errors (infinite where the data do not determine it)
  Eigen::MatrixXd covariance;
  Eigen::MatrixXd correlation;
  double rss_start = 0.0;
  double rss = 0.0;  // of the weighted residuals
  int residuals = 0;
  int unknowns = 0;
  double sigma2 = 0.0;         // RSS / (N - p)
  Eigen::VectorXd column_rms;  // RMS of model - data per column, in the data's units
  int rank = 0;
  double condition = 0.0;                      // of the column-scaled Jacobian
  std::vector<std::vector<int>> undetermined;  // unknowns mixed in each lost direction
  int evaluations = 0;                         // trajectories integrated
  int jacobian_evaluations = 0;                // of which with sensitivities
  std::vector<FitStage> stages;
  bool converged = false;
  std::string stop_reason;
  double seconds = 0.0;
  FlowStatistics statistics;
};

// Fits; the system is only read. Throws std::invalid_argument for an inconsistent problem (sizes,
// indices, bounds, no more residuals than unknowns) and IntegrationError if the trajectory cannot
// be integrated at the starting values.
TrajectoryFitResult fit_trajectory(const OdeSystem& system, const TrajectoryFitProblem& problem,
                                   const TrajectoryFitOptions& options = {});

// The number of residuals the problem has (samples x columns, less those left out at t0).
int residual_count(const TrajectoryFitProblem& problem);

}  // namespace sympathy
