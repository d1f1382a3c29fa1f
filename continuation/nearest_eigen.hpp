// Eigenvectors of an equilibrium's Jacobian by the eigenvalue they belong to: the Hopf point's
// q, the codimension-two points' q and p, the pair a Hopf curve switches to. Internal to the
// continuation layer.
#pragma once

#include <cmath>
#include <complex>
#include <limits>
#include <optional>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

namespace sympathy::detail {

// The eigenvector of `m` for its eigenvalue nearest `target` (unit length), and that eigenvalue.
inline Eigen::VectorXcd eigenvector_nearest(const Eigen::MatrixXd& m, std::complex<double> target,
                                            std::complex<double>* value) {
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(m.cast<std::complex<double>>());
  Eigen::Index best = 0;
  for (Eigen::Index i = 1; i < solver.eigenvalues().size(); ++i)
    if (std::abs(solver.eigenvalues()[i] - target) < std::abs(solver.eigenvalues()[best] - target))
      best = i;
  if (value) *value = solver.eigenvalues()[best];
  return solver.eigenvectors().col(best).normalized();
}

// q with A q = lambda q (|q| = 1) and p with A^T p = conj(lambda) p, <p, q> = p^H q = 1, for the
// eigenvalue nearest `target`; nullopt where <p, q> vanishes.
struct EigenPair {
  std::complex<double> lambda;
  Eigen::VectorXcd q, p;
};
inline std::optional<EigenPair> eigen_pair(const Eigen::MatrixXd& a, std::complex<double> target) {
  EigenPair e;
  e.q = eigenvector_nearest(a, target, &e.lambda);
  Eigen::VectorXcd p = eigenvector_nearest(a.transpose(), std::conj(e.lambda), nullptr);
  const std::complex<double> pq = p.dot(e.q);
  if (!(std::abs(pq) > 0.0)) return std::nullopt;
  e.p = p / std::conj(pq);
  return e;
}

// The pair nearest the imaginary axis with imaginary part above zero, other than near `besides`
// (within 1e-6 of it, relative); omega 0 where there is none.
inline double pair_frequency(const Eigen::MatrixXd& a, double besides) {
  const Eigen::ComplexEigenSolver<Eigen::MatrixXd> solver(a, false);
  double best = std::numeric_limits<double>::infinity(), omega = 0.0;
  for (const std::complex<double>& l : solver.eigenvalues()) {
    if (!(l.imag() > 0.0)) continue;
    if (besides > 0.0 && std::abs(l.imag() - besides) <= 1e-6 * besides) continue;
    if (std::abs(l.real()) < best) {
      best = std::abs(l.real());
      omega = l.imag();
    }
  }
  return omega;
}

}  // namespace sympathy::detail
