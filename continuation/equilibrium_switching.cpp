// The other branch of equilibria through a simple branch point (equilibrium_branch.hpp's
// continue_from_branch_point): its direction from the algebraic branching equation on the null
// vectors of [f_x f_p], as the cycles' transcritical switch (branch_switching.cpp) takes it.
#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/SVD>

#include "equilibrium_continuation.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

using detail::EquilibriumContinuation;
using Driver = driver::Callbacks<EquilibriumPoint, EquilibriumEvent>;
using Result = driver::Result<EquilibriumPoint, EquilibriumEvent>;

// The new branch's unit tangent (scaled norm) at the branch point y0 (psi: f_x's left null
// vector there), the root of the branching equation least parallel to `old` (unscaled, may be
// empty: then the root least parallel to the parameter axis... of the two, the one the old
// branch is not); c_ij by forward differences of the exact Jacobian along each null vector.
Eigen::VectorXd new_direction(const EquilibriumContinuation& run, const Eigen::VectorXd& y0,
                              const Eigen::VectorXd& psi, const Eigen::MatrixXd& jacobian,
                              const Eigen::VectorXd& old) {
  const Eigen::VectorXd& w = run.weights();
  const int n = static_cast<int>(jacobian.rows());
  const Eigen::MatrixXd scaled = jacobian * w.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullV);
  const Eigen::MatrixXd kernel = svd.matrixV().rightCols(2);
  // A simple branch point: rank n - 1, so two null vectors; a third small singular value
  // (relative to the largest) makes it a degenerate one, where the equation does not apply.
  const Eigen::VectorXd sv = svd.singularValues();
  if (n >= 2 && sv[n - 2] < 1e-8 * sv[0])
    throw std::runtime_error(
        "branch switching: [f_x f_p] has rank below n - 1 here (not a simple branch point)");
  // 1e-7 in the scaled norm: the Jacobian is exact, so the forward difference is good to about
  // 1e-7 relative (its truncation) and 1e-9 (rounding over the step); ample to choose a root.
  constexpr double h = 1e-7;
  const Eigen::VectorXd winv = w.cwiseInverse();
  const Eigen::VectorXd gradient = jacobian.transpose() * psi;
  const MooreLinearize linearize = run.linearization();
  Eigen::Matrix2d c;
  for (int j = 0; j < 2; ++j) {
    std::string failure;
    const auto hj =
        hessian_along(linearize, y0, psi, gradient, winv.cwiseProduct(kernel.col(j)), h, failure);
    if (!hj) throw std::runtime_error("branch switching: " + failure);
    for (int i = 0; i < 2; ++i) c(i, j) = hj->dot(winv.cwiseProduct(kernel.col(i)));
  }
  Eigen::VectorXd a = w.cwiseProduct(old);
  if (a.norm() > 0.0) a.normalize();
  return winv.cwiseProduct(branching_tangent(c, kernel, a));  // unit in the scaled norm
}

}  // namespace

EquilibriumBranch continue_from_branch_point(const OdeSystem& system,
                                             const EquilibriumProblem& problem,
                                             const EquilibriumEvent& bp, EquilibriumOptions options,
                                             const EquilibriumCallbacks& callbacks) {
  const Stopwatch started;
  EquilibriumProblem checked = problem;
  checked.start_state = bp.state;
  checked.at.reset();
  if (const std::string wrong = checked.problem_with(system); !wrong.empty())
    throw std::invalid_argument("equilibria: " + wrong);
  options.lower = std::min(problem.from, problem.to);
  options.upper = std::max(problem.from, problem.to);
  if (auto wrong = options.validate())
    throw std::invalid_argument("equilibria: " + wrong->message());
  if (bp.type != EquilibriumEventType::BranchPoint)
    throw std::invalid_argument("equilibria: a switch needs a branch point (BP), not " +
                                to_string(bp.type));
  EquilibriumBranch branch;
  branch.parameter = problem.parameter;
  branch.parameter_name = system.parameter_names()[problem.parameter];
  branch.state_names = system.state_names();
  branch.options = options;
  branch.start_values = system.with_parameter(problem.values, problem.parameter, bp.parameter);
  const int n = system.dimension();
  const auto fail = [&](const std::string& why) {
    branch.stop = StopReason::StartFailed;
    branch.stop_reason = why;
    branch.seconds = started.seconds();
    return branch;
  };
  if (bp.parameter < options.lower || bp.parameter > options.upper)
    return fail("the branch point at " + branch.parameter_name + " = " +
                format_double(bp.parameter) + " lies outside the window");

  // The runs' scales: the branch point's state, and its old branch's over the window.
  const auto new_run = [&] {
    EquilibriumContinuation run(system, problem.parameter, branch.start_values, options);
    run.widen_scale(bp.state);
    if (bp.tangent.size() == n + 1 && std::abs(bp.tangent[n]) > 0)
      run.widen_scale(bp.tangent.head(n) / std::abs(bp.tangent[n]) *
                      (options.upper - options.lower));
    return run;
  };
  EquilibriumContinuation probe = new_run();
  Eigen::VectorXd guess(n + 1);
  guess << bp.state, bp.parameter;
  const MooreSolution s = probe.branch_point_near(guess);
  if (!s.converged) return fail("no simple branch point near the one given: " + s.reason);
  const Eigen::VectorXd y0 = s.y;
  const Eigen::VectorXd old = bp.tangent.size() == n + 1 ? bp.tangent : Eigen::VectorXd();
  Eigen::VectorXd tau;
  try {
    tau = new_direction(probe, y0, s.psi, s.jacobian, old);
  } catch (const std::exception& e) {
    return fail(e.what());
  }
  // Oriented so that the forward half goes up in the parameter, or, where the new branch leaves
  // vertically, up in its largest state component (the singular vectors' signs are arbitrary).
  {
    const Eigen::VectorXd scaled = probe.weights().cwiseProduct(tau);
    // The first of the largest (within 1e-6: chu's line moves x and z by as much).
    const double top = scaled.head(n).cwiseAbs().maxCoeff();
    int largest = 0;
    while (std::abs(scaled[largest]) < (1 - 1e-6) * top) ++largest;
    if ((std::abs(scaled[n]) > 1e-3 ? scaled[n] : scaled[largest]) < 0) tau = -tau;
  }
  const double width = options.upper - options.lower;

  // One step each way off the branch point, halved until it corrects onto the new branch; the
  // branch point itself is point 0, between the two (the bordered system is singular there).
  // A corrected step with more than half of itself along the old tangent went back onto the old
  // branch (it moves along it by O(sqrt(h)), the new one leaves it at O(h^2)).
  const auto step_off = [&](EquilibriumContinuation& run, double sign,
                            std::string& why) -> std::optional<EquilibriumPoint> {
    // The new branch's size over the window where it moves in the parameter; where it leaves
    // the branch point vertically (a pitchfork, a line of equilibria) at least states of order
    // one: from the floor (1e-3, for a branch through x = 0) the steps would grow by 5% a point.
    if (std::abs(tau[n]) * run.weights()[n] > 1e-3)
      run.widen_scale(tau.head(n) / std::abs(tau[n]) * width);
    else
      run.widen_scale(Eigen::VectorXd::Ones(n));
    const Eigen::VectorXd t = run.unit(tau);  // unit in this run's norm
    const double expected_old = old.size() ? std::abs(run.dot(t, run.unit(old))) : 0.0;
    double h = options.initial_step;
    for (int tries = 0; tries < 8; ++tries, h *= 0.5) {
      std::string failure;
      auto p = run.correct(y0, sign * t, h, y0 + sign * h * t, failure);
      if (!p) {
        why = "no step off the branch point could be corrected: " + failure;
        continue;
      }
      const Eigen::VectorXd d = run.y_of(*p) - y0;
      if (old.size() && std::abs(run.dot(run.unit(old), d)) / h > expected_old + 0.5) {
        why = "the step off the branch point went back onto the branch it is on";
        continue;
      }
      p->index = 0;
      p->step = h;
      return p;
    }
    return std::nullopt;
  };

  EquilibriumPoint at_bp = probe.make_point(y0, tau, 0);
  at_bp.tangent = tau;
  at_bp.index = 0;
  if (callbacks.on_point) callbacks.on_point(at_bp);
  // Each half numbered from the branch point: 1, 2, ... on one side, -1, -2, ... on the other.
  Result halves[2];
  for (const int sign : {+1, -1}) {
    EquilibriumContinuation run = new_run();
    std::string why;
    auto first = step_off(run, sign, why);
    Result& r = halves[sign > 0 ? 1 : 0];
    if (!first) {
      r.stop = StopReason::StartFailed;
      r.message = why;
      continue;
    }
    Driver cb{{}, {}, {}, callbacks.stop_requested};
    if (callbacks.on_point)
      cb.on_point = [&](const EquilibriumPoint& p) {
        EquilibriumPoint q = p;
        q.index = sign * (p.index + 1);
        callbacks.on_point(q);
      };
    if (callbacks.on_event)
      cb.on_event = [&](const EquilibriumEvent& e) {
        EquilibriumEvent x = e;
        x.after_point = sign > 0 ? e.after_point + 1 : -(e.after_point + 2);
        callbacks.on_event(x);
      };
    r = driver::continuation(run, std::move(*first), detail::equilibrium_driver_options(options),
                             cb);
    if (callbacks.stop_requested && callbacks.stop_requested()) break;
  }
  // Joined: the backward half reversed, the branch point, the forward half.
  const Result& back = halves[0];
  const Result& ahead = halves[1];
  for (auto it = back.points.rbegin(); it != back.points.rend(); ++it) {
    EquilibriumPoint q = *it;
    q.index = -(q.index + 1);
    q.tangent = -q.tangent;
    branch.points.push_back(std::move(q));
  }
  branch.points.push_back(at_bp);
  for (const auto& p : ahead.points) {
    EquilibriumPoint q = p;
    q.index = p.index + 1;
    branch.points.push_back(std::move(q));
  }
  for (auto it = back.events.rbegin(); it != back.events.rend(); ++it) {
    EquilibriumEvent e = *it;
    e.after_point = -(e.after_point + 2);
    branch.events.push_back(std::move(e));
  }
  for (const auto& e : ahead.events) {
    EquilibriumEvent x = e;
    x.after_point = e.after_point + 1;
    branch.events.push_back(std::move(x));
  }
  const bool none = back.points.empty() && ahead.points.empty();
  branch.stop = none ? StopReason::StartFailed
                     : (back.stop == StopReason::Interrupted ? back.stop : ahead.stop);
  branch.stop_reason = "backward: " + back.message + "; forward: " + ahead.message;
  branch.origin =
      "born at the parent branch's BP at " + branch.parameter_name + " = " + format_double(y0[n]);
  branch.seconds = started.seconds();
  return branch;
}

}  // namespace sympathy
