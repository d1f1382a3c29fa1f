// Derivative tensors of f at an equilibrium, on complex vectors: what the normal-form
// coefficients of Hopf points (l1), of generalized Hopf points (l2) and of the other
// codimension-two points of curves of equilibria are made of. Exact where the system evaluates on
// Taylor jets (OdeSystem::taylor_coefficients: every system written as a template, equation
// files among them); else by differences of the exact f_x, to the third derivative.
// Internal to the continuation layer.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <initializer_list>
#include <limits>
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"

namespace sympathy::detail {

// T(u1, ..., uk) = D^k f(x)(u1, ..., uk) from the diagonal values D^k f(x)(v, ..., v) = k! times
// the Taylor coefficient of order k along v, by polarization: T(u1, ..., uk) = 2^(1-k) sum over
// the signs e (e1 = +1) of e1 ... ek times that coefficient along sum_i e_i u_i (each u_i scaled
// to unit length first, so that no sign pattern cancels more than the others: a fifth-order
// tensor on unit vectors from 16 jets loses about 2^5 of the last digit). Without jets, D^k f by
// differences of f_x for k <= 3, else nothing.
class JacobianDerivatives {
 public:
  using Complex = std::complex<double>;

  JacobianDerivatives(const OdeSystem& system, const ParameterValues& p, const Eigen::VectorXd& x)
      : system_(system), p_(p), x_(x) {
    const double size = std::max(1.0, x.lpNorm<Eigen::Infinity>());
    h_b_ = 1e-5 * size;
    h_c_ = 1e-2 * size;  // extrapolated: its rounding eps / (h / 2)^2 is 4e-12
    std::vector<Complex> v(x.size(), 0.0), out(x.size() * (OdeSystem::kMaxTaylorOrder + 1));
    exact_ = system.taylor_coefficients(0.0, x.data(), p.data(), v.data(), 0, out.data());
  }
  // Whether the tensors are exact (jets), and of which orders there are any.
  bool exact() const { return exact_; }
  int highest_order() const { return exact_ ? OdeSystem::kMaxTaylorOrder : 3; }

  // D^k f(x)(u1, ..., uk), k = args.size() from 1 to highest_order(); nullopt above it.
  std::optional<Eigen::VectorXcd> form(std::initializer_list<Eigen::VectorXcd> args) const {
    const int k = static_cast<int>(args.size());
    const int n = static_cast<int>(x_.size());
    if (k < 1 || k > highest_order()) return std::nullopt;
    std::vector<Eigen::VectorXcd> u(args);
    if (!exact_) {
      if (k == 1) return Eigen::VectorXcd(jacobian(x_).cast<Complex>() * u[0]);
      if (k == 2) return B(u[0], u[1]);
      return complex_E(u[0], u[1]) * u[2];
    }
    double scale = 1.0;
    for (auto& w : u) {
      const double norm = w.norm();
      if (norm == 0.0) return Eigen::VectorXcd::Zero(n);
      scale *= norm;
      w /= norm;
    }
    Eigen::VectorXcd sum = Eigen::VectorXcd::Zero(n);
    std::vector<Complex> out(static_cast<std::size_t>(n) * (k + 1));
    for (int signs = 0; signs < (1 << (k - 1)); ++signs) {
      Eigen::VectorXcd v = u[0];
      double product = 1.0;
      for (int i = 1; i < k; ++i) {
        const double e = (signs >> (i - 1)) & 1 ? -1.0 : 1.0;
        v += e * u[i];
        product *= e;
      }
      if (!system_.taylor_coefficients(0.0, x_.data(), p_.data(), v.data(), k, out.data()))
        return std::nullopt;
      for (int i = 0; i < n; ++i) sum[i] += product * out[static_cast<std::size_t>(k) * n + i];
    }
    return Eigen::VectorXcd(sum * (scale / static_cast<double>(1 << (k - 1))));
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
    if (exact_) return *form({u, v});
    const Eigen::MatrixXcd d = D(u.real()).cast<Complex>() + Complex(0, 1) * D(u.imag());
    return d * v;
  }
  // C(u, u, v), complex trilinear, u in the first two places.
  Eigen::VectorXcd C(const Eigen::VectorXcd& u, const Eigen::VectorXcd& v) const {
    if (exact_) return *form({u, u, v});
    return complex_E(u, u) * v;
  }

  // B(u, v) and C(u, v, w) for real directions.
  Eigen::VectorXd B(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
    if (exact_) return form({u.cast<Complex>(), v.cast<Complex>()})->real();
    return D(u) * v;
  }
  Eigen::VectorXd C(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                    const Eigen::VectorXd& w) const {
    if (exact_) return form({u.cast<Complex>(), v.cast<Complex>(), w.cast<Complex>()})->real();
    return E(u, v) * w;
  }

 private:
  // E(u, v) for complex u and v, bilinear: from the real E of their parts.
  Eigen::MatrixXcd complex_E(const Eigen::VectorXcd& u, const Eigen::VectorXcd& v) const {
    const Eigen::VectorXd a = u.real(), b = u.imag(), c = v.real(), d = v.imag();
    return (E(a, c) - E(b, d)).cast<Complex>() + Complex(0, 1) * (E(a, d) + E(b, c));
  }

  const OdeSystem& system_;
  const ParameterValues& p_;
  const Eigen::VectorXd& x_;
  double h_b_, h_c_;
  bool exact_ = false;
};

}  // namespace sympathy::detail
