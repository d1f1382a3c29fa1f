// The data of a Hopf point: frequency, eigenvector and the first Lyapunov coefficient.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "jacobian_derivatives.hpp"
#include "nearest_eigen.hpp"
#include "sympathy/continuation/equilibrium.hpp"

namespace sympathy {

namespace {

using Complex = std::complex<double>;

using detail::eigenvector_nearest;
using detail::JacobianDerivatives;

}  // namespace

HopfPoint describe_hopf(const OdeSystem& system, const ParameterValues& p, const Eigen::VectorXd& x,
                        double omega_guess) {
  HopfPoint h;
  h.values = p;
  h.state = x;
  Eigen::MatrixXd a;
  system.jacobian(0.0, x.data(), p.data(), a);
  const Eigen::VectorXcd lambda = sorted_eigenvalues(a);
  Complex target(0.0, omega_guess);
  if (omega_guess <= 0.0) {
    double largest = 0.0;
    for (const auto& l : lambda)
      if (l.imag() > largest) largest = l.imag();
    target = Complex(0.0, largest);
  }
  Complex value;
  Eigen::VectorXcd q = eigenvector_nearest(a, target, &value);
  if (value.imag() < 0) {
    q = q.conjugate().eval();
    value = std::conj(value);
  }
  h.omega = value.imag();
  h.period = h.omega > 0 ? 2 * std::numbers::pi / h.omega : 0.0;
  // The phase of q that makes Re q and Im q orthogonal with |Re q| >= |Im q|: then the small
  // orbit x + eps Re(q e^{i omega t}) starts at its largest excursion along Re q.
  const Complex qq = q.transpose() * q;  // sum q_i^2 = |a|^2 - |b|^2 + 2i <a, b>
  q *= std::exp(Complex(0.0, -0.5 * std::arg(qq)));
  h.eigenvector = q;
  if (h.omega <= 0.0) return h;

  // l1 = Re[<p, C(q,q,qbar)> - 2 <p, B(q, A^-1 B(q,qbar))> + <p, B(qbar, (2 i w - A)^-1 B(q,q))>]
  // / (2 w), with A^T p = -i w p and <p, q> = conj(p)^T q = 1 (Kuznetsov, Elements of Applied
  // Bifurcation Theory, 3rd ed., eq. (3.20)).
  Complex adjoint_value;
  const Eigen::VectorXcd v = eigenvector_nearest(a.transpose(), value, &adjoint_value);
  // A^T v = i w v, so p = conj(v) c has A^T p = -i w p; <p, q> = conj(c) v^T q = 1.
  const Complex vq = v.transpose() * q;
  if (std::abs(vq) == 0.0) return h;
  const Eigen::VectorXcd pa = v.conjugate() * std::conj(1.0 / vq);
  const JacobianDerivatives d(system, p, x);
  const Eigen::VectorXcd qbar = q.conjugate();
  const Eigen::MatrixXcd A = a.cast<Complex>();
  const Eigen::MatrixXcd shifted =
      Complex(0.0, 2.0 * h.omega) * Eigen::MatrixXcd::Identity(a.rows(), a.cols()) - A;
  const Eigen::VectorXcd r1 = A.fullPivLu().solve(d.B(q, qbar));
  const Eigen::VectorXcd r2 = shifted.fullPivLu().solve(d.B(q, q));
  const Complex sum = pa.dot(d.C(q, qbar)) - 2.0 * pa.dot(d.B(q, r1)) + pa.dot(d.B(qbar, r2));
  // c1 = sum / 2 (Kuznetsov's (3.20) is its real part over omega).
  const double l1 = sum.real() / (2.0 * h.omega);
  if (std::isfinite(l1) && std::isfinite(sum.imag())) {
    h.lyapunov = l1;
    h.c1 = 0.5 * sum;
  }
  return h;
}

std::string describe_criticality(const std::optional<double>& lyapunov) {
  if (!lyapunov) return "criticality unknown";
  // Exactly zero where the field's second and third derivatives vanish at the point (a
  // piecewise-linear field: a linear centre, whose family of cycles is vertical): no side.
  char text[64];
  std::snprintf(text, sizeof text, "%s (l1 = %.6g)",
                *lyapunov < 0   ? "supercritical"
                : *lyapunov > 0 ? "subcritical"
                                : "degenerate",
                *lyapunov);
  return text;
}

}  // namespace sympathy
