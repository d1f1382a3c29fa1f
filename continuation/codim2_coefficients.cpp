#include "codim2_coefficients.hpp"

#include <complex>
#include <initializer_list>
#include <limits>

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "jacobian_derivatives.hpp"
#include "nearest_eigen.hpp"

namespace sympathy::detail {

namespace {

Eigen::MatrixXd jacobian_at(const OdeSystem& system, const ParameterValues& p,
                            const Eigen::VectorXd& x) {
  Eigen::MatrixXd a;
  system.jacobian(0.0, x.data(), p.data(), a);
  return a;
}

// [A v; w^T 0]^-1 applied to (r, s), its first n entries; and the transposed system's.
Eigen::VectorXd bordered_solve(const Eigen::MatrixXd& a, const Eigen::VectorXd& v,
                               const Eigen::VectorXd& w, const Eigen::VectorXd& r, double s,
                               bool transposed) {
  const int n = static_cast<int>(a.rows());
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n + 1, n + 1);
  m.topLeftCorner(n, n) = transposed ? Eigen::MatrixXd(a.transpose()) : a;
  m.topRightCorner(n, 1) = v;
  m.bottomLeftCorner(1, n) = w.transpose();
  Eigen::VectorXd rhs(n + 1);
  rhs << r, s;
  return m.fullPivLu().solve(rhs).head(n);
}

}  // namespace

std::optional<BogdanovTakensCoefficients> bogdanov_takens_coefficients(const OdeSystem& system,
                                                                       const ParameterValues& p,
                                                                       const Eigen::VectorXd& x) {
  const Eigen::MatrixXd a = jacobian_at(system, p, x);
  const int n = static_cast<int>(a.rows());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd vext = svd.matrixV().col(n - 1), wext = svd.matrixU().col(n - 1);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  // A q0 = 0 and A^T p1 = 0 from the bordered systems, then the generalized vectors.
  Eigen::VectorXd q0 = bordered_solve(a, wext, vext, zero, 1.0, false);
  Eigen::VectorXd p1 = bordered_solve(a, vext, wext, zero, 1.0, true);
  Eigen::VectorXd q1 = bordered_solve(a, p1, q0, q0, 0.0, false);
  Eigen::VectorXd p0 = bordered_solve(a, q0, p1, p1, 0.0, true);
  if (!(q0.allFinite() && q1.allFinite() && p0.allFinite() && p1.allFinite())) return std::nullopt;
  // The sign convention: q0's largest component positive.
  Eigen::Index k = 0;
  q0.cwiseAbs().maxCoeff(&k);
  if (q0[k] < 0) {
    q0 = -q0;
    q1 = -q1;
  }
  const double mu = q0.norm();
  q0 /= mu;
  q1 /= mu;
  q1 -= q0.dot(q1) * q0;
  const double nu = q0.dot(p0);
  if (!(std::abs(nu) > 0.0)) return std::nullopt;
  p1 /= nu;
  p0 -= p0.dot(q1) * p1;
  p0 /= nu;
  const JacobianDerivatives d(system, p, x);
  const Eigen::VectorXd h20 = d.B(q0, q0), h11 = d.B(q0, q1);
  BogdanovTakensCoefficients c;
  c.a = 0.5 * p1.dot(h20);
  c.b = p0.dot(h20) + p1.dot(h11);
  if (!(std::isfinite(c.a) && std::isfinite(c.b))) return std::nullopt;
  return c;
}

std::optional<double> cusp_coefficient(const OdeSystem& system, const ParameterValues& p,
                                       const Eigen::VectorXd& x) {
  const Eigen::MatrixXd a = jacobian_at(system, p, x);
  const int n = static_cast<int>(a.rows());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd q = svd.matrixV().col(n - 1).normalized();
  Eigen::VectorXd pl = svd.matrixU().col(n - 1);
  if (!(std::abs(pl.dot(q)) > 0.0)) return std::nullopt;
  pl /= pl.dot(q);
  const JacobianDerivatives d(system, p, x);
  const Eigen::VectorXd b = d.B(q, q);
  const Eigen::VectorXd h2 = bordered_solve(a, pl, q, -b, 0.0, false);
  const double c = pl.dot(d.C(q, q, q) + 3.0 * d.B(q, h2)) / 6.0;
  if (!std::isfinite(c)) return std::nullopt;
  return c;
}

namespace {

using Complex = std::complex<double>;

}  // namespace

std::optional<ZeroHopfCoefficients> zero_hopf_coefficients(const OdeSystem& system,
                                                           const ParameterValues& p,
                                                           const Eigen::VectorXd& x) {
  using V = Eigen::VectorXcd;
  const Eigen::MatrixXd a = jacobian_at(system, p, x);
  const double omega = pair_frequency(a, 0.0);
  if (!(omega > 0.0)) return std::nullopt;
  auto zero = eigen_pair(a, 0.0);
  auto pair = eigen_pair(a, Complex(0.0, omega));
  if (!zero || !pair) return std::nullopt;
  // The zero eigenvalue's vectors real: their phase is free, so each is turned by its largest
  // component's before the real part is taken; q0's largest component positive.
  const auto real_of = [](const V& v) {
    Eigen::Index k = 0;
    v.cwiseAbs().maxCoeff(&k);
    return Eigen::VectorXd((v * (std::abs(v[k]) / v[k])).real());
  };
  const V q0 = real_of(zero->q).normalized().cast<Complex>();
  V p0 = real_of(zero->p).cast<Complex>();
  if (!(std::abs(p0.dot(q0)) > 0.0)) return std::nullopt;
  p0 /= std::conj(p0.dot(q0));
  const JacobianDerivatives d(system, p, x);
  const V q1 = pair->q, q1b = q1.conjugate();
  ZeroHopfCoefficients z;
  z.b = 0.5 * p0.dot(d.B(q0, q0)).real();
  z.c = p0.dot(d.B(q1, q1b)).real();
  z.a = pair->p.dot(d.B(q0, q1)).real();
  if (!(std::isfinite(z.b) && std::isfinite(z.c) && std::isfinite(z.a)) || z.b == 0.0)
    return std::nullopt;
  z.s = z.b * z.c > 0 ? 1.0 : z.b * z.c < 0 ? -1.0 : 0.0;
  z.theta = z.a / (2.0 * z.b);
  return z;
}

std::optional<DoubleHopfCoefficients> double_hopf_coefficients(const OdeSystem& system,
                                                               const ParameterValues& p,
                                                               const Eigen::VectorXd& x,
                                                               double omega0) {
  using V = Eigen::VectorXcd;
  const Eigen::MatrixXd a = jacobian_at(system, p, x);
  const double omega1 = pair_frequency(a, omega0);
  if (!(omega0 > 0.0) || !(omega1 > 0.0)) return std::nullopt;
  const auto first = eigen_pair(a, Complex(0.0, omega0));
  const auto second = eigen_pair(a, Complex(0.0, omega1));
  if (!first || !second) return std::nullopt;
  const int n = static_cast<int>(a.rows());
  const Eigen::MatrixXcd A = a.cast<Complex>(), I = Eigen::MatrixXcd::Identity(n, n);
  const Complex i0(0.0, first->lambda.imag()), i1(0.0, second->lambda.imag());
  const JacobianDerivatives d(system, p, x);
  const V q0 = first->q, q0b = q0.conjugate(), q1 = second->q, q1b = q1.conjugate();
  const auto solve = [](const Eigen::MatrixXcd& m, const V& r) {
    return V(m.fullPivLu().solve(r));
  };
  // The second-order terms h_jklm of w0^j conj(w0)^k w1^l conj(w1)^m (Kuznetsov 1999).
  const V h1100 = solve(-A, d.B(q0, q0b)), h2000 = solve(2.0 * i0 * I - A, d.B(q0, q0));
  const V h1010 = solve((i0 + i1) * I - A, d.B(q0, q1));
  const V h1001 = solve((i0 - i1) * I - A, d.B(q0, q1b));
  const V h0020 = solve(2.0 * i1 * I - A, d.B(q1, q1)), h0011 = solve(-A, d.B(q1, q1b));
  const auto T = [&](std::initializer_list<V> args) { return *d.form(args); };
  const Complex g2100 =
      first->p.dot(0.5 * T({q0, q0, q0b}) + d.B(q0, h1100) + 0.5 * d.B(h2000, q0b));
  const Complex g1011 =
      first->p.dot(T({q0, q1, q1b}) + d.B(q0, h0011) + d.B(q1, h1001) + d.B(q1b, h1010));
  const Complex h1110 = second->p.dot(T({q1, q0, q0b}) + d.B(q1, h1100) +
                                      d.B(q0, V(h1001.conjugate())) + d.B(q0b, h1010));
  const Complex h0021 =
      second->p.dot(0.5 * T({q1, q1, q1b}) + d.B(q1, h0011) + 0.5 * d.B(h0020, q1b));
  DoubleHopfCoefficients c;
  c.p11 = g2100.real();
  c.p12 = g1011.real();
  c.p21 = h1110.real();
  c.p22 = h0021.real();
  if (!(std::isfinite(c.p11) && std::isfinite(c.p12) && std::isfinite(c.p21) &&
        std::isfinite(c.p22)) ||
      c.p11 == 0.0 || c.p22 == 0.0)
    return std::nullopt;
  c.theta = c.p12 / c.p22;
  c.delta = c.p21 / c.p11;
  return c;
}

std::optional<double> second_lyapunov_coefficient(const OdeSystem& system, const ParameterValues& p,
                                                  const Eigen::VectorXd& x, double omega) {
  using Complex = std::complex<double>;
  using V = Eigen::VectorXcd;
  const JacobianDerivatives d(system, p, x);
  if (d.highest_order() < 5 || !(omega > 0.0)) return std::nullopt;
  const Eigen::MatrixXd a = jacobian_at(system, p, x);
  const int n = static_cast<int>(a.rows());
  const Eigen::MatrixXcd A = a.cast<Complex>(), I = Eigen::MatrixXcd::Identity(n, n);
  const Complex iw(0.0, omega);
  // q and p from the eigenvectors nearest +-i omega.
  const auto pair = eigen_pair(a, iw);
  if (!pair) return std::nullopt;
  const V& q = pair->q;
  const V& pv = pair->p;
  const V qb = q.conjugate();
  const auto T = [&](std::initializer_list<V> args) { return *d.form(args); };
  const auto solve = [](const Eigen::MatrixXcd& m, const V& r) {
    return V(m.fullPivLu().solve(r));
  };
  // The homological equations order by order (Kuznetsov 1999), h_jk the coefficient of
  // z^j conj(z)^k / (j! k!) in the centre manifold's expansion, g21 = 2 c1 = <p, r21>; the
  // normal form's z' = c1 z^2 conj(z) in d(h20 z^2 / 2)/dt gives h31's 3 g21 h20.
  const V h20 = solve(2.0 * iw * I - A, T({q, q}));
  const V h11 = solve(-A, T({q, qb}));
  const V h02 = h20.conjugate();
  const V h30 = solve(3.0 * iw * I - A, T({q, q, q}) + 3.0 * T({q, h20}));
  const V r21 = T({q, q, qb}) + T({qb, h20}) + 2.0 * T({q, h11});
  const Complex g21 = pv.dot(r21);
  // (i omega - A) h21 = r21 - g21 q, solvable since <p, r21 - g21 q> = 0; <p, h21> = 0.
  Eigen::MatrixXcd bordered = Eigen::MatrixXcd::Zero(n + 1, n + 1);
  bordered.topLeftCorner(n, n) = iw * I - A;
  bordered.topRightCorner(n, 1) = q;
  bordered.bottomLeftCorner(1, n) = pv.adjoint();
  V rhs(n + 1);
  rhs << r21 - g21 * q, 0.0;
  const V h21 = solve(bordered, rhs).head(n);
  const V h12 = h21.conjugate();
  const V h31 = solve(2.0 * iw * I - A, T({q, q, q, qb}) + 3.0 * T({q, q, h11}) +
                                            3.0 * T({q, qb, h20}) + 3.0 * T({h20, h11}) +
                                            3.0 * T({q, h21}) + T({qb, h30}) - 3.0 * g21 * h20);
  // (At l1 = 0, Re g21 = 0: the term 4 Re(g21) h11 of the z^2 conj(z)^2 equation vanishes.)
  const V h22 =
      solve(-A, T({q, q, qb, qb}) + 4.0 * T({q, qb, h11}) + T({qb, qb, h20}) + T({q, q, h02}) +
                    2.0 * T({h11, h11}) + 2.0 * T({q, h12}) + 2.0 * T({qb, h21}) + T({h20, h02}));
  const V r32 = T({q, q, q, qb, qb}) + T({q, q, q, h02}) + 3.0 * T({q, qb, qb, h20}) +
                6.0 * T({q, q, qb, h11}) + T({qb, qb, h30}) + 3.0 * T({q, q, h12}) +
                6.0 * T({q, qb, h21}) + 3.0 * T({q, h20, h02}) + 6.0 * T({q, h11, h11}) +
                6.0 * T({qb, h20, h11}) + 2.0 * T({qb, h31}) + 3.0 * T({q, h22}) + T({h30, h02}) +
                3.0 * T({h20, h12}) + 6.0 * T({h11, h21});
  const double l2 = pv.dot(r32).real() / (12.0 * omega);
  if (!std::isfinite(l2)) return std::nullopt;
  return l2;
}

}  // namespace sympathy::detail
