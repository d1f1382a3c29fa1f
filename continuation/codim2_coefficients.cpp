#include "codim2_coefficients.hpp"

#include <Eigen/SVD>

#include "jacobian_derivatives.hpp"

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

}  // namespace sympathy::detail
