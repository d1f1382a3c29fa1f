#include "sympathy/continuation/convergence_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/Eigenvalues>

#include "sympathy/core/flow.hpp"

namespace sympathy {

OptionCheck CertificateOptions::validate() const {
  if (!(radius > 0.0 && radius <= 0.5)) return OptionProblem{"radius", "a number in (0, 0.5]"};
  if (returns < 1 || returns > 100) return OptionProblem{"returns", "an integer from 1 to 100"};
  if (!(slack >= 0.0 && slack < 1.0)) return OptionProblem{"slack", "a number in [0, 1)"};
  if (!(margin > 0.0 && margin < 0.5)) return OptionProblem{"margin", "a number in (0, 0.5)"};
  return std::nullopt;
}

OrbitNeighbourhood::OrbitNeighbourhood(const OdeSystem& system, const PeriodicOrbit& orbit,
                                       CertificateOptions certificate)
    : options(certificate), parameters(orbit.parameters) {
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  if (!orbit.converged() || !(orbit.period > 0.0))
    throw std::invalid_argument("a convergence certificate needs a converged periodic orbit");
  point = orbit.state0;
  period = orbit.period;
  rate = orbit.floquet.max_modulus;
  eligible = orbit.floquet.stability == Stability::Stable &&
             rate < 1.0 - std::max(options.margin, 10.0 * orbit.floquet.trivial_error);
  // One integration over the period: the monodromy, and on the way the amplitude of each state,
  // sampled at 400 points (a range to 1e-5 relative for a smooth orbit).
  const int n = system.dimension();
  Eigen::VectorXd low = point, high = point;
  std::vector<double> times(401);
  // (the last exactly the period: period * 400 / 400 may round above it, beyond the run)
  for (int i = 0; i < 400; ++i) times[i] = period * i / 400.0;
  times[400] = period;
  Flow flow(system);
  const Eigen::MatrixXd m =
      flow.advance_with_sensitivities(point, parameters, 0.0, period, true, {}, times,
                                      [&](double, const Eigen::VectorXd& z) {
                                        low = low.cwiseMin(z);
                                        high = high.cwiseMax(z);
                                      })
          .transition;
  scale = 0.5 * (high - low);
  const double largest = scale.maxCoeff();
  for (int i = 0; i < n; ++i) scale[i] = std::max(scale[i], 1e-3 * largest);
  Eigen::VectorXd f(n);
  system.rhs(0.0, point.data(), parameters.data(), f.data());
  normal = f.cwiseQuotient(scale);
  normal.normalize();
  // The monodromy's eigenvectors in the scaled coordinates, each of unit inf-norm; the trivial
  // one is the best aligned with f.
  const Eigen::MatrixXd scaled = scale.cwiseInverse().asDiagonal() * m * scale.asDiagonal();
  const Eigen::EigenSolver<Eigen::MatrixXd> solver(scaled);
  Eigen::MatrixXcd v = solver.eigenvectors();
  int trivial = 0;
  double best = -1.0;
  for (int i = 0; i < n; ++i) {
    const double aligned = std::abs(v.col(i).normalized().dot(normal.cast<std::complex<double>>()));
    if (aligned > best) {
      best = aligned;
      trivial = i;
    }
    v.col(i) /= v.col(i).cwiseAbs().maxCoeff();
  }
  const Eigen::MatrixXcd inverse = v.inverse();
  coordinates.resize(n - 1, n);
  modes.resize(n, n - 1);
  multipliers.resize(n - 1);
  for (int i = 0, k = 0; i < n; ++i)
    if (i != trivial) {
      coordinates.row(k) = inverse.row(i);
      multipliers[k] = solver.eigenvalues()[i];
      modes.col(k++) = v.col(i);
    }
}

ConvergenceCertificate::ConvergenceCertificate(
    const OdeSystem& system, std::shared_ptr<const OrbitNeighbourhood> neighbourhood, double reach)
    : system_(system), orbit_(std::move(neighbourhood)), reach_(reach) {
  if (!orbit_) throw std::invalid_argument("ConvergenceCertificate: no orbit");
}

double ConvergenceCertificate::side(const Eigen::VectorXd& z) const {
  return orbit_->normal.dot((z - orbit_->point).cwiseQuotient(orbit_->scale));
}

double ConvergenceCertificate::near(const Eigen::VectorXd& z) const {
  return (z - orbit_->point).cwiseQuotient(orbit_->scale).lpNorm<Eigen::Infinity>();
}

double ConvergenceCertificate::bound(const std::vector<int>& components) const {
  if (last_.size() == 0) return std::numeric_limits<double>::infinity();
  double b = 0.0;
  for (Eigen::Index i = 0; i < last_.size(); ++i) {
    double largest = components.empty() ? 1.0 : 0.0;
    for (int j : components) largest = std::max(largest, std::abs(orbit_->modes(j, i)));
    b += std::abs(last_[i]) * largest;
  }
  return b;
}

bool ConvergenceCertificate::add(double t, const Eigen::VectorXd& z) {
  const double g = side(z);
  const bool crossed = has_previous_ && g_previous_ < 0.0 && g >= 0.0;
  // Only near z* (within reach_): the hyperplane is crossed far from the orbit too.
  if (crossed && std::min(near(z_previous_), near(z)) < reach_) {
    // Cubic Hermite between the two samples, f at both; the crossing by regula falsi on it.
    const int n = system_.dimension();
    Eigen::VectorXd f0(n), f1(n);
    system_.rhs(t_previous_, z_previous_.data(), orbit_->parameters.data(), f0.data());
    system_.rhs(t, z.data(), orbit_->parameters.data(), f1.data());
    const double h = t - t_previous_;
    const auto at = [&](double s) -> Eigen::VectorXd {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * z_previous_ + (s3 - 2 * s2 + s) * h * f0 +
             (-2 * s3 + 3 * s2) * z + (s3 - s2) * h * f1;
    };
    double lo = 0.0, hi = 1.0, g_lo = g_previous_, g_hi = g;
    double s = 0.5;
    for (int k = 0; k < 60 && hi - lo > 1e-13; ++k) {
      s = std::clamp(lo - g_lo * (hi - lo) / (g_hi - g_lo), lo + 0.01 * (hi - lo),
                     hi - 0.01 * (hi - lo));
      const double gs = side(at(s));
      if (gs < 0.0) {
        lo = s;
        g_lo = gs;
      } else {
        hi = s;
        g_hi = gs;
      }
    }
    times_.push_back(t_previous_ + s * h);
    const Eigen::VectorXcd c =
        orbit_->coordinates *
        (at(s) - orbit_->point).cwiseQuotient(orbit_->scale).cast<std::complex<double>>();
    distances_.push_back(c.cwiseAbs().maxCoeff());
    last_ = c;
    const OrbitNeighbourhood& o = *orbit_;
    const int m = o.options.returns;
    const std::size_t k = distances_.size();
    if (o.eligible && !certified_ && k > static_cast<std::size_t>(m)) {
      bool near = distances_[k - m - 1] < o.options.radius;
      for (std::size_t j = k - m; j < k; ++j)
        near =
            near && distances_[j] < o.options.radius &&
            // (1e-7: the interpolation's floor, where a start on the orbit stays)
            distances_[j] <= (o.rate + o.options.slack * (1 - o.rate)) * distances_[j - 1] + 1e-7 &&
            std::abs(times_[j] - times_[j - 1] - o.period) <= 0.05 * o.period;
      certified_ = certified_ || near;
    }
  }
  has_previous_ = true;
  t_previous_ = t;
  g_previous_ = g;
  z_previous_ = z;
  return certified_;
}

RestCertificate::RestCertificate(const OdeSystem& system, const ParameterValues& p,
                                 const Eigen::VectorXd& rest, CertificateOptions options)
    : system_(system), p_(p), rest_(rest), options_(options), f_(rest.size()) {
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  const auto n = rest.size();
  Eigen::MatrixXd a(n, n);
  system.jacobian(0.0, rest.data(), p.data(), a);
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(a);
  if (eigen.info() != Eigen::Success) return;
  const Eigen::VectorXcd& lambda = eigen.eigenvalues();
  alpha_ = lambda.real().maxCoeff();
  const double largest = lambda.cwiseAbs().maxCoeff();
  if (!(alpha_ < -options.margin * largest)) return;
  const Eigen::MatrixXcd v = eigen.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(v);
  coordinates_ = lu.inverse();
  const double condition =
      v.cwiseAbs().colwise().sum().maxCoeff() * coordinates_.cwiseAbs().colwise().sum().maxCoeff();
  if (!(condition <= 1e8)) return;
  scale_ = std::max(1.0, rest.lpNorm<Eigen::Infinity>());
  eligible_ = true;
}

bool RestCertificate::add(const Eigen::VectorXd& z) {
  if (certified_ || !eligible_) return certified_;
  const Eigen::VectorXcd c = coordinates_ * (z - rest_).cast<std::complex<double>>();
  const double size = c.squaredNorm();
  if (size == 0.0) return certified_ = true;  // at x* itself
  system_.rhs(0.0, z.data(), p_.data(), f_.data());
  const double falling = c.dot(coordinates_ * f_.cast<std::complex<double>>()).real() / size;
  const bool inside = c.cwiseAbs().maxCoeff() <= options_.radius * scale_;
  if (!(inside && falling <= (1.0 - options_.slack) * alpha_)) {
    streak_start_ = std::numeric_limits<double>::quiet_NaN();
    return false;
  }
  if (std::isnan(streak_start_)) streak_start_ = size;
  certified_ = size <= streak_start_ * std::exp(-2.0);
  return certified_;
}

}  // namespace sympathy
