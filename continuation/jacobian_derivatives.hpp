// Derivatives of f's Jacobian along directions, by differences of the exact f_x (f's second
// and third derivatives are not in the OdeSystem interface): what the normal-form coefficients
// of Hopf points (l1) and of the codimension-two points on curves of equilibria are made of.
// Internal to the continuation layer.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"

namespace sympathy::detail {

// Derivatives of f_x along directions, by central differences of the exact f_x (f's second and
// third derivatives are not in the OdeSystem interface). D(w) = sum_j w_j d(f_x)/dx_j and
// E(u, w) = sum_jk u_j w_k d2(f_x)/dx_j dx_k, for real directions, at steps h_b and h_c: their
// truncation errors are O(h_b^2) and (extrapolated) O(h_c^4), their rounding errors O(eps / h).
// and O(eps / h^2).
class JacobianDerivatives {
 public:
  using Complex = std::complex<double>;

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

  // B(u, v) and C(u, v, w) for real directions (C by the extrapolated E).
  Eigen::VectorXd B(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const { return D(u) * v; }
  Eigen::VectorXd C(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                    const Eigen::VectorXd& w) const {
    return E(u, v) * w;
  }

 private:
  const OdeSystem& system_;
  const ParameterValues& p_;
  const Eigen::VectorXd& x_;
  double h_b_, h_c_;
};

}  // namespace sympathy::detail
