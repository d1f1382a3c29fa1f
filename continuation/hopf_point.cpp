// The data of a Hopf point: frequency, eigenvector and the first Lyapunov coefficient.
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>

#include <Eigen/Eigenvalues>

#include "sympathy/continuation/equilibrium.hpp"

namespace sympathy {

namespace {

using Complex = std::complex<double>;

// The eigenvector of `a` for its eigenvalue nearest `target`, unit length.
Eigen::VectorXcd eigenvector_near(const Eigen::MatrixXd& a, Complex target, Complex& value) {
  Eigen::ComplexEigenSolver<Eigen::MatrixXcd> solver(a.cast<Complex>());
  Eigen::Index best = 0;
  for (Eigen::Index i = 1; i < solver.eigenvalues().size(); ++i)
    if (std::abs(solver.eigenvalues()[i] - target) < std::abs(solver.eigenvalues()[best] - target))
      best = i;
  value = solver.eigenvalues()[best];
  return solver.eigenvectors().col(best).normalized();
}

// Derivatives of f_x along directions, by central differences of the exact f_x (f's second and
// third derivatives are not in the OdeSystem interface). D(w) = sum_j w_j d(f_x)/dx_j and
// E(u, w) = sum_jk u_j w_k d2(f_x)/dx_j dx_k, for real directions, at steps h_b and h_c: their
// truncation errors are O(h_b^2) and (extrapolated) O(h_c^4), their rounding errors O(eps / h).
// and O(eps / h^2).
class JacobianDerivatives {
 public:
  JacobianDerivatives(const OdeSystem& system, const ParameterValues& p, const Eigen::VectorXd& x)
      : system_(system), p_(p), x_(x) {
    const double size = std::max(1.0, x.lpNorm<Eigen::Infinity>());
    h_b_ = 1e-5 * size;
    h_c_ = 1e-2 * size;  // extrapolated: its rounding eps / (h / 2)^2 is 4e-12
  }
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& at) const {
    Eigen::MatrixXd j;
    system_.jacobian(0.0, at.data(), p_.data(), j);
    return j;
  }
  Eigen::MatrixXd D(const Eigen::VectorXd& w) const {
    return (jacobian(x_ + h_b_ * w) - jacobian(x_ - h_b_ * w)) / (2 * h_b_);
  }
  // Richardson's extrapolation of the h and h / 2 differences, O(h^4): the h difference alone,
  // O(h^2) at h = 1e-3, put abc's l1 7.7e-5 off (exact -0.03103708510 from symbolic
  // derivatives; now 4e-9) and the Bautin normal form's generalized Hopf point 3e-6 off. Where f
  // is steep on the scale of h (the metronomes' tanh escapement, its slope 1000 in the angular
  // velocity: their l1 was -1216.54 at h = 1e-3 and is -3066.6, the extrapolations at 1e-5 and
  // 5e-6 agreeing to 1.4e-5) the step is divided by ten until the extrapolations at h and h / 2
  // agree to 1e-6 of their size; the best agreeing pair is kept (rounding, eps |f_x| / h^2,
  // bounds how far down that helps).
  Eigen::MatrixXd E(const Eigen::VectorXd& u, const Eigen::VectorXd& w) const {
    const auto extrapolated = [&](double h) {
      return Eigen::MatrixXd((4 * E_at(u, w, 0.5 * h) - E_at(u, w, h)) / 3);
    };
    Eigen::MatrixXd best = extrapolated(h_c_);
    double best_gap = std::numeric_limits<double>::infinity();
    for (double h = h_c_; h >= 1e-5 * h_c_; h *= 0.1) {
      const Eigen::MatrixXd coarse = extrapolated(h), fine = extrapolated(0.5 * h);
      const double size = std::max(fine.norm(), 1e-300);
      const double gap = (coarse - fine).norm() / size;
      if (gap < best_gap) {
        best_gap = gap;
        best = fine;
      }
      if (gap <= 1e-6) break;
    }
    return best;
  }
  Eigen::MatrixXd E_at(const Eigen::VectorXd& u, const Eigen::VectorXd& w, double h) const {
    return (jacobian(x_ + h * (u + w)) - jacobian(x_ + h * (u - w)) - jacobian(x_ - h * (u - w)) +
            jacobian(x_ - h * (u + w))) /
           (4 * h * h);
  }
  // B(u, v) = sum_jk f_ijk u_j v_k, complex bilinear.
  Eigen::VectorXcd B(const Eigen::VectorXcd& u, const Eigen::VectorXcd& v) const {
    const Eigen::MatrixXcd d = D(u.real()).cast<Complex>() + Complex(0, 1) * D(u.imag());
    return d * v;
  }
  // C(u, u, v), complex trilinear, u in the first two places.
  Eigen::VectorXcd C(const Eigen::VectorXcd& u, const Eigen::VectorXcd& v) const {
    const Eigen::VectorXd a = u.real(), b = u.imag();
    const Eigen::MatrixXcd e = (E(a, a) - E(b, b)).cast<Complex>() + Complex(0, 2) * E(a, b);
    return e * v;
  }

 private:
  const OdeSystem& system_;
  const ParameterValues& p_;
  const Eigen::VectorXd& x_;
  double h_b_, h_c_;
};

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
  Eigen::VectorXcd q = eigenvector_near(a, target, value);
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
  const Eigen::VectorXcd v = eigenvector_near(a.transpose(), value, adjoint_value);
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
  char text[64];
  std::snprintf(text, sizeof text, "%s (l1 = %.6g)",
                *lyapunov < 0 ? "supercritical" : "subcritical", *lyapunov);
  return text;
}

}  // namespace sympathy
