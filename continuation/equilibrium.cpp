#include "sympathy/continuation/equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Eigenvalues>

namespace sympathy {

OptionCheck EquilibriumNewtonOptions::validate() const {
  if (!positive(tolerance) || tolerance >= 1e-2)
    return OptionProblem{"tolerance", "a positive number below 0.01"};
  if (max_iterations < 1 || max_iterations > 100)
    return OptionProblem{"max_iterations", "an integer from 1 to 100"};
  return std::nullopt;
}

Eigen::VectorXcd sorted_eigenvalues(const Eigen::MatrixXd& jacobian) {
  Eigen::EigenSolver<Eigen::MatrixXd> solver(jacobian, false);
  Eigen::VectorXcd v = solver.eigenvalues();
  std::vector<std::complex<double>> s(v.data(), v.data() + v.size());
  std::sort(s.begin(), s.end(), [](const auto& a, const auto& b) {
    if (a.real() != b.real()) return a.real() > b.real();
    return a.imag() > b.imag();
  });
  for (std::size_t i = 0; i < s.size(); ++i) v[static_cast<Eigen::Index>(i)] = s[i];
  return v;
}

std::complex<double> nearest_eigenvalue(const Eigen::VectorXcd& eigenvalues,
                                        std::complex<double> target) {
  std::complex<double> best = eigenvalues[0];
  for (const auto& l : eigenvalues)
    if (std::abs(l - target) < std::abs(best - target)) best = l;
  return best;
}

int unstable_count(const Eigen::VectorXcd& eigenvalues, double tolerance) {
  const double size = std::max(1.0, eigenvalues.size() ? eigenvalues.cwiseAbs().maxCoeff() : 0.0);
  int n = 0;
  for (const auto& l : eigenvalues)
    if (l.real() > tolerance * size) ++n;
  return n;
}

Equilibrium solve_equilibrium(const OdeSystem& system, const ParameterValues& p,
                              const Eigen::VectorXd& guess,
                              const EquilibriumNewtonOptions& options) {
  Equilibrium e;
  e.parameters = p;
  e.state = guess;
  const int n = system.dimension();
  if (guess.size() != n) {
    e.reason =
        "the guess has " + std::to_string(guess.size()) + " states; expected " + std::to_string(n);
    return e;
  }
  Eigen::MatrixXd J(n, n);
  Eigen::VectorXd f = system.rhs(0.0, e.state, p);
  for (int it = 0; it < options.max_iterations; ++it) {
    if (!f.allFinite()) {
      e.reason = "f is not finite at the iterate";
      return e;
    }
    system.jacobian(0.0, e.state.data(), p.data(), J);
    Eigen::FullPivLU<Eigen::MatrixXd> lu(J);
    if (!lu.isInvertible()) {
      e.reason = "df/dx is singular at the iterate";
      return e;
    }
    const Eigen::VectorXd dx = lu.solve(-f);
    e.state += dx;
    f = system.rhs(0.0, e.state, p);
    e.iterations = it + 1;
    if (dx.lpNorm<Eigen::Infinity>() <=
        options.tolerance * std::max(1.0, e.state.lpNorm<Eigen::Infinity>())) {
      e.converged = f.allFinite();
      break;
    }
  }
  e.residual = f.lpNorm<Eigen::Infinity>();
  if (!e.converged) {
    e.reason = "Newton did not converge in " + std::to_string(options.max_iterations) +
               " iterations (|f| = " + std::to_string(e.residual) + ")";
    return e;
  }
  system.jacobian(0.0, e.state.data(), p.data(), J);
  e.eigenvalues = sorted_eigenvalues(J);
  e.unstable = unstable_count(e.eigenvalues);
  return e;
}

}  // namespace sympathy
