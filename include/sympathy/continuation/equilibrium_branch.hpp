// Branches of equilibria in one parameter, with their folds (LP), branch points (BP) and Hopf
// points (HB), as AUTO's IPS = 1 runs and BifurcationKit's `continuation` of a steady state.
//
// Unknowns Y = (x, p). Pseudo-arclength: f(x, p) = 0 and <tau, Y - Y_a> = ds in a scaled norm
// (states by the largest |x|_inf met on the branch, at least `state_scale_floor`, the parameter by
// the window's width). Newton on that bordered system with df/dx and df/dp from the system's
// dual numbers: exact derivatives, so a point converges quadratically.
//
// Test functions between consecutive points a and b, each regular where its event is:
//   LP: the tangent's parameter component (changes sign where the branch turns);
//   BP: det [f_x f_p; tau^T] (changes sign where two branches cross: the tangent is oriented
//       continuously through it, the bordered determinant is not);
//   HB: the real part of a complex pair of eigenvalues of f_x, the pair followed from a to b by
//       least total distance (core/assignment.hpp).
// Each is located by the Illinois variant of regula falsi in the arclength from a, each probe
// corrected onto the branch, until the bracket in the parameter is below `location_tolerance`
// (relative to |p|, with a floor of 1% of the window).
#pragma once

#include <complex>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/driver.hpp"
#include "sympathy/continuation/equilibrium.hpp"

namespace sympathy {

struct EquilibriumOptions {
  double lower = 0.0, upper = 0.0;  // the window; the branch stops on its edges
  double initial_step = 0.01;       // scaled arclength
  double min_step = 1e-7;
  double max_step = 0.05;
  int max_points = 1000;
  int max_iterations = 6;           // corrector iterations per step (a step needing more is halved)
  double tolerance = 1e-12;         // of the corrector's last step, relative to max(1, |x|_inf)
  double state_scale_floor = 1e-3;  // the scaled norm measures states from at least this
  double min_tangent_cosine = 0.95;   // a step that turns the tangent more is halved
  double location_tolerance = 1e-10;  // relative, in the parameter
  bool detect_bifurcations = true;
  // Parameter values at which to report the branch's equilibrium (AUTO's UZ), each where the
  // branch passes it, solved there with the parameter held (exact).
  std::vector<double> user_points;

  OptionCheck validate() const;
};

enum class EquilibriumEventType {
  Fold,         // LP: a real eigenvalue through 0 where the branch turns
  BranchPoint,  // BP: a real eigenvalue through 0 where two branches cross
  Hopf,         // HB: a complex pair through the imaginary axis
  UserPoint,    // UZ: a parameter value asked for (EquilibriumOptions::user_points)
};
std::string to_string(EquilibriumEventType t);  // "LP", "BP", "HB", "UZ"

struct EquilibriumPoint {
  int index = 0;  // along the branch; negative on the backward part of a two-way run
  double parameter = 0.0;
  Eigen::VectorXd state;
  Eigen::VectorXcd eigenvalues;  // largest real part first
  int unstable = 0;
  double residual = 0.0;    // |f|_inf
  Eigen::VectorXd tangent;  // unit (dx, dp) in the scaled norm
  double step = 0.0;        // scaled arclength from the point before
  int iterations = 0;
};

struct EquilibriumEvent {
  EquilibriumEventType type = EquilibriumEventType::Fold;
  double parameter = 0.0;
  // How far the true point may lie from `parameter`: the final bracket's width.
  double uncertainty = 0.0;
  bool located = false;
  Eigen::VectorXd state;
  Eigen::VectorXcd eigenvalues;
  double residual = 0.0;
  std::optional<HopfPoint> hopf;  // HB: the crossing pair, its eigenvector, its criticality
  Eigen::VectorXd tangent;        // the branch's at the event (for a switch at a BP)
  int after_point = 0;
  double arclength = 0.0;  // from that point
  std::string note;
};

struct EquilibriumBranch {
  std::string parameter_name;
  int parameter = -1;
  std::vector<std::string> state_names;
  std::vector<EquilibriumPoint> points;  // in order along the branch
  std::vector<EquilibriumEvent> events;  // in order along the branch
  StopReason stop = StopReason::ParameterBound;
  std::string stop_reason;
  EquilibriumOptions options;
  ParameterValues start_values;
  std::string origin;  // a switched branch's: the branch point it was born at
  double seconds = 0.0;
  bool started() const { return stop != StopReason::StartFailed; }
};

// What to continue: as BranchProblem, from an equilibrium near `start_state`.
struct EquilibriumProblem {
  int parameter = -1;
  ParameterValues values;
  double from = 0.0, to = 0.0;
  std::optional<double> at;  // start here and go both ways
  Eigen::VectorXd start_state;
  EquilibriumNewtonOptions newton;

  // What is wrong with it for `system` (empty when nothing).
  std::string problem_with(const OdeSystem& system) const;
  double first_value() const { return at ? *at : from; }
};

struct EquilibriumCallbacks {
  std::function<void(const EquilibriumPoint&)> on_point;
  std::function<void(const EquilibriumEvent&)> on_event;
  std::function<bool()> stop_requested;
};

// The branch through the equilibrium near problem.start_state at the first value, to `to` (and
// from `at` to `from` first, for a two-way run, joined in parameter order). Options' bounds are
// set from the problem. Throws std::invalid_argument for a problem or options out of their
// domain.
EquilibriumBranch continue_equilibria(const OdeSystem& system, const EquilibriumProblem& problem,
                                      EquilibriumOptions options,
                                      const EquilibriumCallbacks& callbacks = {});

// The other branch through the simple branch point `bp` (an event of a branch in
// problem.parameter: its state and parameter, a guess that Moore's system refines, and its
// `tangent`, the old branch's direction there, which tells the two roots of the branching
// equation apart; empty: the root least parallel to nothing, either), continued both ways within
// problem.from .. problem.to (problem.values: the other parameters; problem.start_state and `at`
// are not used). Its points are numbered from the branch point (0) outwards, negative on one
// side, as a switched branch of cycles; its origin names the branch point. The direction is the
// root of the algebraic branching equation psi^T F_yy[t, t] = 0 on the null vectors of [f_x f_p]
// not along the old branch (F_yy by differences of the exact Jacobian), the first step off each
// way corrected onto the new branch (refused where it falls back onto the old one). A start that
// fails (no simple branch point near bp, no step off it) is a StartFailed branch with the reason.
// Throws std::invalid_argument for a problem or options out of their domain or a bp that is not
// a BP.
EquilibriumBranch continue_from_branch_point(const OdeSystem& system,
                                             const EquilibriumProblem& problem,
                                             const EquilibriumEvent& bp, EquilibriumOptions options,
                                             const EquilibriumCallbacks& callbacks = {});

}  // namespace sympathy
