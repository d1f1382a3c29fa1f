// Moore's regular system for a simple branch point of cycles (branch_point.hpp), and its use by
// the continuation run: a branch point located by its crossing multiplier, away from a symmetric
// subspace, is moved to the system's solution.
#include "sympathy/continuation/branch_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/multiplier_tracking.hpp"

namespace sympathy {

namespace {

// Forward-difference step of the second derivatives, in the scaled norm: the Jacobians carry
// the sensitivities' error of about 1e-11 relative, so the differences are good to about 1e-5,
// and their truncation error is of the same order; Newton then contracts by about 1e-5 a step.
constexpr double kDifferenceStep = 1e-6;

}  // namespace

MooreLinearize shooting_linearization(ShootingProblem& problem, const PhaseSection& section,
                                      const BranchSpace& space, int parameter) {
  return [&problem, &section, &space, parameter](const Eigen::VectorXd& y) {
    MooreLinearization l;
    const int N = problem.unknowns();
    try {
      const auto e = problem.evaluate(y.head(N), space.values_at(y[N]), section, true, parameter);
      l.jacobian = Eigen::MatrixXd(problem.jacobian(e, true));
      l.residual = e.residual;
    } catch (const std::exception& ex) {
      l.failure = ex.what();
      return l;
    }
    l.ok = l.residual.allFinite() && l.jacobian.allFinite();
    if (!l.ok) l.failure = "the residual or its Jacobian is not finite";
    return l;
  };
}

std::optional<Eigen::VectorXd> hessian_along(const MooreLinearize& linearize,
                                             const Eigen::VectorXd& y, const Eigen::VectorXd& psi,
                                             const Eigen::VectorXd& gradient,
                                             const Eigen::VectorXd& direction, double h,
                                             std::string& failure) {
  const MooreLinearization d = linearize(y + h * direction);
  if (!d.ok) {
    failure = d.failure;
    return std::nullopt;
  }
  return Eigen::VectorXd((d.jacobian.transpose() * psi - gradient) / h);
}

Eigen::VectorXd branching_tangent(const Eigen::Matrix2d& c, const Eigen::MatrixXd& kernel,
                                  const Eigen::VectorXd& old) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(0.5 * (c + c.transpose()));
  const double l1 = eig.eigenvalues()[0], l2 = eig.eigenvalues()[1];
  if (!(l1 * l2 < 0.0))
    throw std::runtime_error(
        "branch switching: the branching equation has no two real roots here (not a simple "
        "branch point)");
  // In the eigenvectors' coordinates l1 u^2 + l2 v^2 = 0: (u, v) = (sqrt|l2|, +-sqrt|l1|).
  Eigen::VectorXd best;
  double best_cos = 2.0;
  for (const double sign : {+1.0, -1.0}) {
    const Eigen::Vector2d uv(std::sqrt(std::abs(l2)), sign * std::sqrt(std::abs(l1)));
    const Eigen::VectorXd t = (kernel * (eig.eigenvectors() * uv)).normalized();
    const double cosine = std::abs(t.dot(old));
    if (cosine < best_cos) {
      best_cos = cosine;
      best = t;
    }
  }
  // The other root is the old branch: within the differences' error of the old tangent.
  return best;
}

MooreSolution solve_moore(const MooreLinearize& linearize, const Eigen::VectorXd& w,
                          const Eigen::VectorXd& guess, double residual_noise,
                          double jacobian_noise, const BranchPointOptions& options) {
  MooreSolution out;
  const int N = static_cast<int>(guess.size()) - 1;
  const int size = 2 * N + 2;  // y, psi, beta
  Eigen::VectorXd y = guess;
  MooreLinearization at = linearize(y);
  ++out.evaluations;
  if (!at.ok) {
    out.reason = "integration failed: " + at.failure;
    return out;
  }
  // psi from the smallest singular value of F_y with comparable (scaled) columns.
  const Eigen::MatrixXd scaled = at.jacobian * w.cwiseInverse().asDiagonal();
  Eigen::VectorXd psi =
      Eigen::JacobiSVD<Eigen::MatrixXd>(scaled, Eigen::ComputeFullU).matrixU().col(N - 1);
  double beta = 0.0;
  // Columns of the Newton matrix in the scaled y (and psi, beta as they are).
  Eigen::VectorXd column_scale = Eigen::VectorXd::Ones(size);
  column_scale.head(N + 1) = w.cwiseInverse();
  double last_step = std::numeric_limits<double>::infinity();
  for (int it = 0; it < options.max_iterations; ++it) {
    out.iterations = it;
    const Eigen::VectorXd gradient = at.jacobian.transpose() * psi;  // F_y^T psi
    Eigen::VectorXd g(size);
    g.head(N) = at.residual + beta * psi;
    g.segment(N, N + 1) = gradient;
    g[size - 1] = 0.5 * (psi.squaredNorm() - 1.0);
    // d(F_y^T psi)/dy: the Hessian of psi^T F, symmetric; its differences symmetrized.
    Eigen::MatrixXd hessian(N + 1, N + 1);
    for (int j = 0; j <= N; ++j) {
      std::string failure;
      const auto column =
          hessian_along(linearize, y, psi, gradient, Eigen::VectorXd::Unit(N + 1, j),
                        kDifferenceStep / w[j], failure);
      ++out.evaluations;
      if (!column) {
        out.reason = "integration failed: " + failure;
        return out;
      }
      hessian.col(j) = *column;
    }
    hessian = 0.5 * (hessian + hessian.transpose()).eval();
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(size, size);
    a.block(0, 0, N, N + 1) = at.jacobian;
    a.block(0, N + 1, N, N) = beta * Eigen::MatrixXd::Identity(N, N);
    a.block(0, size - 1, N, 1) = psi;
    a.block(N, 0, N + 1, N + 1) = hessian;
    a.block(N, N + 1, N + 1, N) = at.jacobian.transpose();
    a.block(size - 1, N + 1, 1, N) = psi.transpose();
    const Eigen::MatrixXd a_scaled = a * column_scale.asDiagonal();
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(a_scaled);
    if (qr.rank() < size) {
      out.reason = "the system is singular at the guess (not a simple branch point)";
      return out;
    }
    const Eigen::VectorXd dz = column_scale.cwiseProduct(qr.solve(-g));
    const Eigen::VectorXd dy = dz.head(N + 1);
    const double step = w.cwiseProduct(dy).norm();
    if (!std::isfinite(step)) {
      out.reason = "the Newton step is not finite";
      return out;
    }
    // Converged, or, after two steps, at the integration's noise (a step within a hundred
    // times the tolerance): the point is y as it stands, the step counted in its uncertainty.
    if (step <= options.step_tolerance || (it >= 2 && step <= 100 * options.step_tolerance)) {
      out.converged = true;
      out.y = y;
      out.psi = psi;
      out.residual = at.residual.cwiseAbs().maxCoeff();
      out.beta = beta;
      // e_p^T A^-1 dG for errors dG of F and of F_y (times |psi| = 1) in each entry, with the
      // worst signs: |v|_1-weighted, v = A^-T e_p. F's error is at least |F| here: the exact
      // problem has a branch point with F = 0 (beta = 0), so what is left of F (-beta psi) is
      // the integration's error breaking it (3.4e-9 on lcbp at rtol 1e-11, atol 1e-13, where
      // the corrector's attainable tolerance says 1e-10).
      const Eigen::VectorXd v =
          a.transpose().colPivHouseholderQr().solve(Eigen::VectorXd::Unit(size, N));
      out.uncertainty = std::abs(dy[N]) +
                        std::max(residual_noise, out.residual) * v.head(N).cwiseAbs().sum() +
                        jacobian_noise * v.segment(N, N + 1).cwiseAbs().sum();
      out.jacobian = std::move(at.jacobian);
      return out;
    }
    if (it > 1 && step > last_step) {
      out.reason = "Newton diverged (a scaled step of " + std::to_string(step) + " after " +
                   std::to_string(last_step) + ")";
      return out;
    }
    y += dy;
    psi += dz.segment(N + 1, N);
    beta += dz[size - 1];
    last_step = step;
    at = linearize(y);
    ++out.evaluations;
    if (!at.ok) {
      out.reason = "integration failed: " + at.failure;
      return out;
    }
  }
  out.reason = "no convergence in " + std::to_string(options.max_iterations) + " Newton steps";
  return out;
}

BranchPointSolution solve_branch_point(ShootingProblem& problem, const PhaseSection& section,
                                       const BranchSpace& space, int parameter,
                                       const Eigen::VectorXd& guess, double residual_noise,
                                       double monodromy_noise, const BranchPointOptions& options) {
  BranchPointSolution out;
  const int N = problem.unknowns();
  if (N + 1 > options.max_unknowns) {
    out.reason = std::to_string(N + 1) + " unknowns: above the " +
                 std::to_string(options.max_unknowns) +
                 " for which the system's second derivatives are affordable";
    return out;
  }
  const MooreSolution s =
      solve_moore(shooting_linearization(problem, section, space, parameter), space.weights(),
                  guess, residual_noise, monodromy_noise, options);
  out.reason = s.reason;
  out.iterations = s.iterations;
  out.evaluations = s.evaluations;
  if (!s.converged) return out;
  try {
    // The solution's evaluation with derivatives, for its point (one more integration).
    out.evaluation =
        problem.evaluate(s.y.head(N), space.values_at(s.y[N]), section, true, parameter);
    ++out.evaluations;
  } catch (const std::exception& ex) {
    out.reason = std::string("integration failed: ") + ex.what();
    return out;
  }
  out.converged = true;
  out.y = s.y;
  out.residual = s.residual;
  out.beta = s.beta;
  out.uncertainty = s.uncertainty;
  return out;
}

void Continuation::refine_branch_point(Bifurcation& e, const ContinuationPoint& a,
                                       const ContinuationPoint& b) const {
  // Where the crossing is already regular: a symmetry-breaking crossing, the branch held in its
  // subspace (the paper's branch points); several multipliers at once or a family's neutral
  // directions make the point no simple branch point.
  if (e.type != BifurcationType::BranchPoint || !e.located() || e.multiplicity != 1 ||
      e.symmetry == SymmetryKind::Breaking || family_dimension_ > 0)
    return;
  const int N = problem_->unknowns();
  Eigen::VectorXd guess(N + 1);
  guess << e.unknowns, e.parameter;
  const double residual_noise = corrector_tolerance();
  const double monodromy_noise =
      std::max(e.floquet.trivial_error, std::numeric_limits<double>::epsilon());
  const BranchPointSolution s = solve_branch_point(*problem_, a.section, *space_, parameter_, guess,
                                                   residual_noise, monodromy_noise);
  const double lo = std::min(a.parameter, b.parameter), hi = std::max(a.parameter, b.parameter);
  if (!s.converged || s.y[N] < lo || s.y[N] > hi) {
    const std::string why =
        s.converged ? "its solution left the step that found the crossing" : s.reason;
    e.note += (e.note.empty() ? "" : "; ") +
              std::string("located by the crossing alone (the regular branch-point system: ") +
              why +
              "): at a transcritical crossing only to about the square root of the "
              "corrector's tolerance";
    // And its uncertainty says so: the orbits near a transcritical crossing are corrected only
    // to the residual over a singular value that vanishes with the distance, which leaves the
    // crossing off by about sqrt(residual error) in units of the parameter's scale (lcbp: 4.4e-5
    // with BDF, residual error 3.4e-9; 1.8e-8 with the CLI's preset).
    const double scale = std::max(std::abs(e.parameter), 0.01 * (options_.upper - options_.lower));
    e.uncertainty = std::max(e.uncertainty, std::sqrt(residual_noise) * scale);
    return;
  }
  Correction c;
  c.converged = true;
  c.y = s.y;
  c.evaluation = s.evaluation;
  c.residual = s.residual;
  c.iterations = s.iterations;
  const ContinuationPoint p = make_point(c, e.tangent, a.index, e.arclength);
  e.parameter = p.parameter;
  e.uncertainty = s.uncertainty;
  e.period = p.orbit.period;
  e.floquet = p.orbit.floquet;
  e.monodromy_growth = p.orbit.monodromy_growth;
  e.state0 = p.orbit.state0;
  e.unknowns = p.unknowns;
  // The old branch's tangent from the step's ends: at the crossing's point, 1e-8 from the branch
  // point, the Jacobian's two smallest singular values are both tiny and its null vector is any
  // mix of the two branches' directions (on lcbp it was the other family's, and switching there
  // followed the old branch).
  Eigen::VectorXd tangent = a.tangent + b.tangent;
  e.tangent = tangent / std::sqrt(space_->dot(tangent, tangent));
  double nearest = std::numeric_limits<double>::infinity();
  for (const auto& m : nontrivial(e.floquet))
    if (std::abs(m.value - 1.0) < nearest) {
      nearest = std::abs(m.value - 1.0);
      e.crossing = m.value;
      e.symmetry = m.symmetry;
    }
  e.note += (e.note.empty() ? "" : "; ") + std::string("located on the regular BP system");
}

}  // namespace sympathy
