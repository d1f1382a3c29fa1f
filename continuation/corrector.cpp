#include "sympathy/continuation/corrector.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <vector>

#include "sympathy/continuation/broyden.hpp"

namespace sympathy {

namespace {

double inf_norm(const Eigen::VectorXd& v) {
  return v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
}

}  // namespace

Correction correct(ShootingProblem& problem, const PhaseSection& section, const BranchSpace& space,
                   int parameter, const CorrectorOptions& options, const Eigen::VectorXd& from,
                   const Eigen::VectorXd& tangent, double step, const Eigen::VectorXd& guess,
                   const Eigen::SparseMatrix<double>* chord) {
  const int N = space.unknowns();
  const double tolerance = options.tolerance;
  Correction c;
  Eigen::VectorXd y = guess;
  const Eigen::VectorXd row = space.arclength_row(tangent);
  auto rhs_at = [&](const Eigen::VectorXd& residual) {
    Eigen::VectorXd rhs(N + 1);
    rhs.head(N) = -residual;
    rhs[N] = -(row.dot(y - from) - step);
    return rhs;
  };
  int iterations = 0;
  // Where the predictions have been landing on the branch, the integration with sensitivities
  // comes first: at the guess it usually both confirms the point and gives its monodromy, and the
  // plain run that would only have said so is saved (on the anti-phase k-branch the orbit does not
  // move with k, every prediction lands, and that plain run was 13% of the fast preset's time and
  // 14% of the default's). Where it does not land, the quasi-Newton steps start from this exact
  // Jacobian instead of the extrapolated one.
  std::optional<ShootingProblem::Evaluation> known;  // with sensitivities, at y
  if (options.derivatives_first) {
    try {
      known = problem.evaluate(y.head(N), space.values_at(y[N]), section, true, parameter);
    } catch (const IntegrationError& error) {
      c.reason = error.what();
      return c;
    }
    const double norm = inf_norm(known->residual);
    if (norm <= closure_tolerance(tolerance, *known)) {
      c.converged = true;
      c.y = std::move(y);
      c.residual = norm;
      c.evaluation = std::move(*known);
      return c;
    }
  }
  // Broyden's updates of `chord` (the Jacobian extrapolated from the last points), in the scaled
  // norm, while they contract.
  if ((chord || known) && options.max_chord_steps > 0) {
    const auto matrix = bordered(known ? problem.jacobian(*known, true) : *chord, row);
    std::vector<Eigen::VectorXd> steps;
    double last = std::numeric_limits<double>::infinity();
    double ratio = 0.1;  // the contraction so far (a guess before two residuals)
    double expected = options.expected_residual;  // the next residual's
    Eigen::VectorXd before = y;
    for (int k = 0; k < options.max_chord_steps; ++k) {
      // Far from the point (the prediction's residual, or the last one's times the contraction
      // above coarse_above tolerances) a coarse run's residual steers as well as a tight one's.
      // One that comes out small is its own error's size and steers nowhere: run tight then (a
      // prediction that landed, as every one on the anti-phase k-branch does, would otherwise
      // take a step on the coarse run's error, and the next point would not start with the run
      // with sensitivities: fast 0.18 -> 0.27 s, default 0.69 -> 0.97 s there).
      if (k > 0) expected = ratio * last;
      const bool given = k == 0 && known;  // the run with sensitivities' own residual
      const bool coarse =
          !given && options.coarse_above > 0.0 && expected > options.coarse_above * tolerance;
      Eigen::VectorXd residual;
      try {
        const ParameterValues values = space.values_at(y[N]);
        residual = given ? known->residual : problem.residual(y.head(N), values, section, coarse);
        if (coarse && inf_norm(residual) <= options.coarse_above * tolerance)
          residual = problem.residual(y.head(N), values, section);
      } catch (const IntegrationError&) {
        y = before;
        break;
      }
      const double norm = inf_norm(residual);
      if (k == 0) c.guess_residual = norm;
      if (norm <= 0.25 * tolerance) break;
      // Not contracting: Newton takes over, from the better of the last two.
      if (norm > 0.5 * last) {
        if (norm > last) y = before;
        break;
      }
      const auto z = broyden_step(solve_linear(matrix, rhs_at(residual), space.linear()).x, steps,
                                  [&](const auto& u, const auto& v) { return space.dot(u, v); });
      if (!z || !z->allFinite()) break;
      steps.push_back(*z);
      before = y;
      y += *z;
      known.reset();  // y moved
      ++c.chord_steps;
      // Where the contraction so far says this step lands within a quarter tolerance, the run
      // with sensitivities below checks it, and the plain run that would only have said so is
      // saved (one of the 5-7 runs a point on the in-phase k-branch, where the orbit moves).
      if (std::isfinite(last) && norm * (norm / last) <= 0.25 * tolerance) break;
      if (std::isfinite(last)) ratio = norm / last;
      last = norm;
    }
  }
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it, ++iterations) {
    ShootingProblem::Evaluation e;
    if (it == 0 && known) {
      e = std::move(*known);  // the chord steps did not move y
    } else {
      try {
        e = problem.evaluate(y.head(N), space.values_at(y[N]), section, true, parameter);
      } catch (const IntegrationError& error) {
        c.reason = error.what();
        return c;
      }
    }
    const double norm = inf_norm(e.residual);
    // Converged; or stalled within ten tolerances: the integration's noise floor, not a failure.
    // An orbit closes to kOrbitClosure of its amplitude too (closure_tolerance): a family
    // shrinking into an equilibrium has, near it, "orbits" whose residual stalls at the decay
    // over one period, which is no orbit (find_periodic_orbit's rule, here for every point).
    const double closure = closure_tolerance(tolerance, e);
    const bool stalled = it >= 1 && norm > 0.3 * previous && norm <= 10 * closure;
    if (norm <= closure || stalled) {
      c.converged = true;
      c.y = std::move(y);
      c.evaluation = std::move(e);
      c.residual = norm;
      c.iterations = iterations;
      return c;
    }
    if (it >= options.max_iterations || (it >= 2 && norm > previous)) {
      std::ostringstream msg;
      msg << "corrector " << (norm > previous ? "diverged" : "did not converge") << " (residual "
          << norm << " after " << iterations << " iterations";
      if (norm <= 10 * tolerance)
        msg << "; no orbit: " << norm / sampled_amplitude(e.samples) << " of an amplitude of "
            << sampled_amplitude(e.samples) << ", where an orbit closes to " << kOrbitClosure;
      msg << ")";
      c.reason = msg.str();
      return c;
    }
    previous = norm;
    const auto dy =
        solve_linear(bordered(problem.jacobian(e, true), row), rhs_at(e.residual), space.linear());
    if (!dy.x.allFinite()) {
      c.reason = "corrector step not finite";
      return c;
    }
    y += dy.x;
  }
}

}  // namespace sympathy
