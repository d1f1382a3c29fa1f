// Whether a run is stiff for its non-stiff integrator, measured on the run itself.
//
// A non-stiff method (Adams with fixed-point iteration, an explicit Runge-Kutta pair) is stable,
// and its fixed point converges, only while h |lambda| stays below a bound of order one for the
// eigenvalues lambda of the Jacobian df/dz. Where its steps are set by accuracy it takes fewer
// steps than BDF (its orders are higher); where they are set by that bound it takes many more, and
// BDF with Newton takes the steps accuracy allows. The indicator is that count measured: the
// non-stiff integrator's steps over one period of the guess (a plain run at the run's own
// tolerance) divided by BDF's over the same period. The bound itself varies with the method's
// order and the iteration (on the row setup, Adams' steps were stability-limited at h rho = 0.72
// with a platform of k = 1e6 N/m, c = 5000 N s/m and accuracy-limited at h rho = 1.1 with
// k = 1e5, c = 500), so h rho alone does not decide; it is measured beside the indicator.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "sympathy/core/flow.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

struct StiffnessEstimate {
  double indicator = 0.0;       // steps / bdf_steps
  long steps = 0;               // the non-stiff integrator's steps over the period
  long bdf_steps = 0;           // BDF's (Newton) over the same period, at the same tolerances
  double rate = 0.0;            // the largest spectral radius rho(J) at the sampled steps (1/s)
  double largest_h_rate = 0.0;  // the largest h rho(J) of the non-stiff integrator's steps there
  double seconds = 0.0;         // what the measurement cost (CPU)
  bool capped = false;          // the non-stiff run stopped at kMeasuredUpTo times BDF's steps
};

// The spectral radius of a square matrix (the largest |eigenvalue|).
double spectral_radius(const Eigen::MatrixXd& a);

// Integrates from z0 over [t0, t0 + period] with BDF and with `nonstiff` at its tolerances (no
// sensitivities; the latter for at most kMeasuredUpTo times BDF's steps), and reads h rho(J) at the
// non-stiff integrator's step ending first after each of `samples` times spread evenly over the
// period. Throws IntegrationError as Flow does (a step limit of `nonstiff` below the cap too).
StiffnessEstimate measure_stiffness(const OdeSystem& system, const FlowOptions& nonstiff,
                                    const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                                    double period, int samples = 32);

// Above this indicator BDF takes over: between the last orbit Adams was faster on and the first
// BDF was (the table beside measure_stiffness in stiffness.cpp; near it either choice is within
// a factor of two of the other).
inline constexpr double kStiffIndicator = 1.4;
// The non-stiff run is stopped at this many times BDF's steps (the indicator is then at least
// this, and StiffnessEstimate::capped says so).
inline constexpr double kMeasuredUpTo = 4.0;

// The flow options a run uses after the measurement: `options` as they are where the indicator is
// at most `threshold` (or they are BDF already), else BDF with Newton and CVODES's forward-
// sensitivity module (cheaper a step than BDF on the augmented system, whose Newton matrix holds
// every column: 0.32 s against 0.41 s on the k = 1e5, c = 500 orbit), the tolerances and step caps
// kept.
FlowOptions after_stiffness(const FlowOptions& options, const StiffnessEstimate& estimate,
                            double threshold = kStiffIndicator);

// "stiffness indicator 0.53 (BDF above 1.5)", for reports.
std::string stiffness_note(const StiffnessEstimate& estimate, double threshold = kStiffIndicator);

}  // namespace sympathy
