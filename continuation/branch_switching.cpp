#include "sympathy/continuation/branch_switching.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "sympathy/continuation/branch_point.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

// The unit vector of span(basis) (orthonormal columns) nearest to c, orthogonal to a (both in the
// same coordinates; a may be empty).
Eigen::VectorXd nearest_in_span(const Eigen::MatrixXd& basis, const Eigen::VectorXd& c,
                                const Eigen::VectorXd& a) {
  Eigen::MatrixXd k = basis;
  if (a.size()) {
    // The span's part orthogonal to a's projection onto it: one dimension less.
    Eigen::VectorXd pa = k * (k.transpose() * a);
    if (pa.norm() > 1e-12 * a.norm()) {
      pa.normalize();
      k -= pa * (pa.transpose() * k);
      // An orthonormal basis of what is left (rank one less).
      Eigen::JacobiSVD<Eigen::MatrixXd> svd(k, Eigen::ComputeThinU);
      k = svd.matrixU().leftCols(basis.cols() - 1);
    }
  }
  Eigen::VectorXd v = k * (k.transpose() * c);
  if (v.norm() < 1e-12 * c.norm())
    throw std::runtime_error(
        "branch switching: the critical direction has no component along the new branch's "
        "directions (not a simple branch point?)");
  return v.normalized();
}

// The eigenvector of M for the real eigenvalue nearest `target` (+1 or -1) that is farthest from
// f (the trivial direction, whose multiplier 1 sits beside a BP's) and, where `across` (the
// complement of the orbit's subspace, columns) is given, has the largest part across it.
Eigen::VectorXd critical_eigenvector(const Eigen::MatrixXd& m, double target,
                                     const Eigen::VectorXd& f, const Eigen::MatrixXd& across) {
  const Eigen::EigenSolver<Eigen::MatrixXd> eig(m);
  const int n = static_cast<int>(m.rows());
  // The two eigenvalues nearest the target (a BP's and the trivial one near +1).
  std::vector<int> order(n);
  for (int i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return std::abs(eig.eigenvalues()[a] - target) < std::abs(eig.eigenvalues()[b] - target);
  });
  const Eigen::VectorXd fn = f.size() ? Eigen::VectorXd(f.normalized()) : Eigen::VectorXd();
  Eigen::VectorXd best;
  double best_score = -1.0;
  for (int k = 0; k < std::min(n, 2); ++k) {
    Eigen::VectorXd v = eig.eigenvectors().col(order[k]).real();
    if (v.norm() == 0.0) v = eig.eigenvectors().col(order[k]).imag();
    v.normalize();
    if (fn.size()) v -= fn * fn.dot(v);  // the trivial direction's part out
    if (across.cols()) v = across * (across.transpose() * v);
    const double score = v.norm();
    if (score > best_score) {
      best_score = score;
      best = v;
    }
  }
  if (!(best_score > 1e-6))
    throw std::runtime_error(
        "branch switching: no critical eigenvector apart from the trivial one");
  return best.normalized();
}

}  // namespace

Eigen::VectorXd Continuation::branching_direction(
    const PhaseSection& section, const Eigen::VectorXd& y0, const Eigen::MatrixXd& jacobian,
    const Eigen::VectorXd& psi, const Eigen::MatrixXd& kernel, const Eigen::VectorXd& old) const {
  // The algebraic branching equation on the kernel {phi_1, phi_2} (scaled): the tangents
  // t = a phi_1 + b phi_2 of the branches through the point solve
  //   sum_ij c_ij t_i t_j = 0,   c_ij = psi^T F_yy[phi_i, phi_j],
  // two real directions at a simple branch point (c indefinite). F_yy[., phi_j] by a forward
  // difference of the sensitivities' Jacobians along phi_j: one evaluation each.
  const Eigen::VectorXd winv = space_->weights().cwiseInverse();
  constexpr double h = 1e-6;  // scaled: Jacobians good to about 1e-11 relative, so c to 1e-5
  Eigen::Matrix2d c;
  const Eigen::VectorXd gradient = jacobian.transpose() * psi;
  const MooreLinearize linearize = shooting_linearization(*problem_, section, *space_, parameter_);
  for (int j = 0; j < 2; ++j) {
    std::string failure;
    const auto hj =
        hessian_along(linearize, y0, psi, gradient, winv.cwiseProduct(kernel.col(j)), h, failure);
    if (!hj) throw std::runtime_error("branch switching: " + failure);
    for (int i = 0; i < 2; ++i) c(i, j) = hj->dot(winv.cwiseProduct(kernel.col(i)));
  }
  return branching_tangent(c, kernel, old);
}

Branch Continuation::run_switched(const PeriodicOrbit& base, const Eigen::VectorXd& critical,
                                  const Eigen::VectorXd& old_tangent,
                                  const ContinuationCallbacks& callbacks, SwitchStart& start,
                                  const Eigen::MatrixXd& mirror, bool transcritical) {
  if (!system_.autonomous())
    throw std::invalid_argument("branch switching: for autonomous systems (not yet forced ones)");
  const int N = problem_->unknowns();
  system_.check_parameters(base.parameters);
  subspace_ = base.subspace;
  space_ = std::make_unique<BranchSpace>(system_, *problem_, parameter_, base.parameters,
                                         options_.upper - options_.lower,
                                         options_.orbit.newton.rank_tolerance);
  space_->reset_scales(base.state0, base.period, options_.orbit.transient_flow);
  // The new direction has the size of the orbit: the orbit at the event does not show it (a
  // component that is zero there, the platform of an anti-phase orbit) and its scale would be the
  // floor, 1e-3 of the largest, making the first steps a thousand times too short.
  const int n = problem_->dimension();
  Eigen::VectorXd sizes = critical.head(n).cwiseAbs();
  if (sizes.maxCoeff() > 0.0) sizes *= space_->sizes().maxCoeff() / sizes.maxCoeff();
  space_->include_sizes(sizes);
  const BranchSpace& space = *space_;
  const double p0 = system_.parameter(base.parameters, parameter_);
  const PhaseSection section = space.section(base.state0, p0);
  Eigen::VectorXd y0(N + 1);
  y0.head(N) = problem_->unknowns_from(base.state0, base.parameters, base.period);
  y0[N] = p0;
  const auto e = problem_->evaluate(y0.head(N), base.parameters, section, true, parameter_);
  family_dimension_ = base.family_dimension;
  predictions_land_ = false;  // the steps off the event: plain runs first, as from a start

  // The null space of [F_x F_p] in the scaled norm: the right singular vectors of J W^-1 with the
  // smallest singular values, two (the old branch and the new) plus the family's.
  const Eigen::VectorXd w = space.weights();
  const Eigen::MatrixXd jacobian(problem_->jacobian(e, true));
  const Eigen::MatrixXd scaled = jacobian * w.cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const int k = std::min(N + 1, 2 + base.family_dimension);
  const Eigen::MatrixXd kernel = svd.matrixV().rightCols(k);
  // The constraint: orthogonal to the old tangent, or no parameter component.
  const Eigen::VectorXd a = old_tangent.size() == N + 1
                                ? Eigen::VectorXd(w.asDiagonal() * old_tangent)
                                : Eigen::VectorXd(Eigen::VectorXd::Unit(N + 1, N));
  Eigen::VectorXd tau;
  double expected_old = 0.0;  // the new direction's own component along the old tangent
  if (transcritical && old_tangent.size() == N + 1 && k == 2) {
    tau = branching_direction(section, y0, jacobian, svd.matrixU().col(N - 1), kernel,
                              a.normalized());
    expected_old = std::abs(tau.dot(a.normalized()));
  } else {
    tau = nearest_in_span(kernel, w.asDiagonal() * critical, a);
  }
  tau = w.cwiseInverse().asDiagonal() * tau;  // unit in the scaled norm
  start.direction = tau;

  // One step each way along it, halved until it corrects. The event itself, where the Jacobian
  // is singular, is never a point of the new branch: it lies between the two first points.
  // Along the new branch the old one is left at O(h^2): the step's component along the old
  // tangent, over h, is the new branch's curvature times h (a pitchfork's p - p_0 = c s^2), and
  // falls as h does; a corrector that went back onto the old branch instead moved along it by
  // O(sqrt(h)), which grows relative to h as h falls. So a step with more than half of itself
  // along the old tangent is retried at half the length, and refused when that does not help.
  auto step_off = [&](double sign) {
    const double old_norm =
        old_tangent.size() == N + 1 ? std::sqrt(space.dot(old_tangent, old_tangent)) : 0.0;
    double h = options_.initial_step;
    std::string why;
    for (int tries = 0; tries < 8; ++tries, h *= 0.5) {
      const Correction c = correct_step(section, y0, sign * tau, h, y0 + sign * h * tau, nullptr);
      if (!c.converged) {
        why = "no step off the event could be corrected: " + c.reason;
        continue;
      }
      if (old_norm > 0.0) {
        const double along_old = std::abs(space.dot(old_tangent, c.y - y0)) / (old_norm * h);
        if (along_old > expected_old + 0.5) {
          why =
              "the step off the event went back onto the branch it started on (its component "
              "along the old tangent is " +
              format_double(along_old) + " of the step)";
          continue;
        }
        start.old_branch_component = std::max(start.old_branch_component, along_old);
      }
      start.off_event = std::max(start.off_event, std::sqrt(space.dot(c.y - y0, c.y - y0)));
      return make_point(c, sign * tau, 0, h).orbit;
    }
    throw std::runtime_error("branch switching: " + why);
  };
  const PeriodicOrbit ahead = step_off(+1.0);
  // With a mirror the other half is not computed but reflected (below).
  const PeriodicOrbit behind = mirror.size() ? ahead : step_off(-1.0);
  // The event itself, as the joined branch's point 0: where both halves start.
  Correction at_event;
  at_event.converged = true;
  at_event.y = y0;
  at_event.evaluation = e;
  at_event.residual = e.residual.cwiseAbs().maxCoeff();
  ContinuationPoint event_point = make_point(at_event, tau, 0, 0.0);
  event_point.orbit.newton.reason = "the event the branch was born at";

  // Away from the event from each: the run from `behind` is the joined branch's backward part.
  int sign = +1;
  ContinuationCallbacks inner;
  inner.stop_requested = callbacks.stop_requested;
  // Numbered from the event (0): 1, 2, ... away from it on one side, -1, -2, ... on the other.
  auto joined_index = [&](int index) { return sign * (index + 1); };
  auto joined_after = [&](int after) { return sign > 0 ? after + 1 : -(after + 2); };
  if (callbacks.on_point) callbacks.on_point(event_point);
  inner.on_point = [&](const ContinuationPoint& p) {
    if (!callbacks.on_point) return;
    ContinuationPoint q = p;
    q.index = joined_index(p.index);
    callbacks.on_point(q);
  };
  inner.on_event = [&](const Bifurcation& event) {
    if (!callbacks.on_event) return;
    Bifurcation b = event;
    b.after_point = joined_after(event.after_point);
    callbacks.on_event(b);
  };
  const Eigen::VectorXd widened = space.sizes();
  const int toward = tau[N] >= 0.0 ? +1 : -1;
  Branch away = run_from(ahead, toward, inner, tau, widened);
  if (callbacks.stop_requested && callbacks.stop_requested()) return away;
  sign = -1;
  Branch back;
  if (mirror.size()) {
    // The other half is this one reflected: every state, segment, tangent and section mapped by
    // the reflection, the period and the parameter as they are, the multipliers the same.
    back = away;
    const int m = problem_->segments();
    auto reflect = [&](Eigen::VectorXd y) {
      for (int j = 0; j < m && y.size() >= (j + 1) * n; ++j)
        y.segment(j * n, n) = mirror * y.segment(j * n, n);
      return y;
    };
    for (auto& p : back.points) {
      p.orbit.state0 = mirror * p.orbit.state0;
      p.unknowns = reflect(p.unknowns);
      p.tangent = reflect(p.tangent);
      if (p.section.through.size() == n) p.section.through = mirror * p.section.through;
      if (p.section.normal.size() == n) p.section.normal = mirror * p.section.normal;
      inner.on_point(p);
    }
    for (auto& ev : back.events) {
      ev.state0 = mirror * ev.state0;
      ev.unknowns = reflect(ev.unknowns);
      ev.tangent = reflect(ev.tangent);
      ev.note += std::string(ev.note.empty() ? "" : "; ") + "the mirror image of the other half's";
      inner.on_event(ev);
    }
    back.flow = FlowStatistics{};
    back.seconds = 0.0;
  } else {
    back = run_from(behind, -toward, inner, -tau, widened);
  }
  // Joined by the driver's join, numbered from the event (0): each half's points and events one
  // on, the event first in the forward half (its start, the one point the join keeps once).
  for (Branch* half : {&away, &back}) {
    for (auto& p : half->points) ++p.index;
    for (auto& ev : half->events) ++ev.after_point;
  }
  away.points.insert(away.points.begin(), std::move(event_point));
  Branch joined = join_branches(std::move(back), std::move(away));
  return joined;
}

Branch switch_branch(const OdeSystem& system, const Branch& branch, const Bifurcation& event,
                     const ContinuationOptions& options, const ContinuationCallbacks& callbacks,
                     SwitchStart* start) {
  const bool doubling = event.type == BifurcationType::PeriodDoubling;
  if (event.type != BifurcationType::BranchPoint && !doubling)
    throw std::invalid_argument(
        "branch switching: at a branch point (BP) or a period doubling "
        "(PD), not at a " +
        describe(event.type) + " (" + to_string(event.type) + ")");
  if (!event.located())
    throw std::invalid_argument("branch switching: the " + to_string(event.type) + " at " +
                                branch.parameter_name + " = " + format_double(event.parameter) +
                                " was not located (" + to_string(event.location) + ")");
  if (branch.parameter < 0 || branch.start_values.size() != system.parameter_values_size())
    throw std::invalid_argument("branch switching: the branch is not one of this system");
  SwitchStart s;
  const ParameterValues values =
      system.with_parameter(branch.start_values, branch.parameter, event.parameter);
  // The orbit's subspace and family, from the branch point before the event.
  PeriodicOrbit base;
  base.parameters = values;
  base.state0 = event.state0;
  base.period = event.period;
  base.segments = options.orbit.shooting.segments;
  for (const auto& p : branch.points)
    if (p.index == event.after_point) {
      base.family_dimension = p.orbit.family_dimension;
      base.subspace = p.orbit.subspace;
    }

  // The critical eigenvector from the monodromy at the event.
  ShootingProblem problem(system, options.orbit.shooting);
  const auto e = problem.evaluate(problem.unknowns_from(event.state0, values, event.period), values,
                                  problem.section_through(event.state0, values), true);
  const Eigen::VectorXd f = system.rhs(0.0, event.state0, values);
  const Eigen::MatrixXd across =
      event.symmetry == SymmetryKind::Breaking && !base.subspace.is_whole_space()
          ? base.subspace.bases(system.dimension()).across
          : Eigen::MatrixXd();
  s.critical = critical_eigenvector(monodromy(e.transitions), doubling ? -1.0 : 1.0, f, across);

  // A pitchfork out of a subspace whose reflection R = 2P - I (P the orthogonal projection onto
  // it) is a symmetry of f (f(R z) = R f(z), checked at sample states to 1e-12 relative): the two
  // halves of the new branch are each other's images (R v = -v for the breaking eigenvector), so
  // the second is the first reflected, not computed again. Anti-phase x = 0, th2 = -th1 is the
  // fixed space of R (x, th1, th2) = (-x, -th2, -th1).
  Eigen::MatrixXd mirror;
  if (event.symmetry == SymmetryKind::Breaking && !base.subspace.is_whole_space() && !doubling) {
    const int n = system.dimension();
    const auto bases = base.subspace.bases(n);
    const Eigen::MatrixXd r =
        2.0 * bases.inside * bases.inside.transpose() - Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd scale =
        event.state0.cwiseAbs().cwiseMax(1e-3 * event.state0.cwiseAbs().maxCoeff());
    const double defect =
        equivariance_defect(system, values, scale, [&](const Eigen::VectorXd& z) { return r * z; });
    if (defect < 1e-12) mirror = r;
  }

  // The new branch breaks the subspace's symmetry (BP of a breaking multiplier) or doubles the
  // period (PD): it is continued in the whole space.
  if (event.symmetry == SymmetryKind::Breaking || doubling) base.subspace = InvariantSubspace();
  if (doubling) base.period *= 2.0;

  Continuation continuation(system, branch.parameter, options);
  // The critical direction in the unknowns: each segment's state carries it along the orbit
  // (the segments of the new problem: of the doubled period for a PD).
  // (A BP's segments are the event's own, already integrated; a PD's are of the doubled period.)
  ShootingProblem::Evaluation doubled;
  if (doubling) {
    doubled = problem.evaluate(problem.unknowns_from(base.state0, values, base.period), values,
                               problem.section_through(base.state0, values), true);
  }
  const ShootingProblem::Evaluation& eb = doubling ? doubled : e;
  const int n = system.dimension(), m = problem.segments();
  Eigen::VectorXd critical = Eigen::VectorXd::Zero(problem.unknowns() + 1);
  Eigen::VectorXd v = s.critical;
  for (int j = 0; j < m; ++j) {
    critical.segment(j * n, n) = v;
    v = eb.transitions[j] * v;
  }
  // The old tangent (BP: the same unknowns; PD: unknown in the doubled ones, see run_switched).
  // (An event located before the branch was refined onto more segments has a tangent in fewer
  // unknowns: none then, as for a PD.)
  const Eigen::VectorXd old_tangent = doubling || event.tangent.size() != problem.unknowns() + 1
                                          ? Eigen::VectorXd()
                                          : event.tangent;
  base.floquet = FloquetAnalysis();
  base.newton.converged = true;
  // A BP that breaks no declared symmetry (two families crossing, lcbp's circles): the new
  // branch's tangent from the branching equation, not orthogonal to the old one.
  const bool transcritical = !doubling && event.symmetry != SymmetryKind::Breaking;
  Branch born =
      continuation.run_switched(base, critical, old_tangent, callbacks, s, mirror, transcritical);
  born.origin = to_string(event.type) + " at " + branch.parameter_name + " = " +
                format_double(event.parameter) + (doubling ? " (period doubled)" : "");
  s.base = base;
  if (start) *start = s;
  return born;
}

}  // namespace sympathy
