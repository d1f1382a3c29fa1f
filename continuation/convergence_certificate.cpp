#include "sympathy/continuation/convergence_certificate.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sympathy/core/flow.hpp"

namespace sympathy {

OptionCheck CertificateOptions::validate() const {
  if (!(radius > 0.0 && radius <= 0.5)) return OptionProblem{"radius", "a number in (0, 0.5]"};
  if (returns < 1 || returns > 100) return OptionProblem{"returns", "an integer from 1 to 100"};
  if (!(margin > 0.0 && margin < 0.5)) return OptionProblem{"margin", "a number in (0, 0.5)"};
  return std::nullopt;
}

ConvergenceCertificate::ConvergenceCertificate(const OdeSystem& system, const PeriodicOrbit& orbit,
                                               CertificateOptions options)
    : system_(system), options_(options), parameters_(orbit.parameters) {
  if (auto wrong = options_.validate()) throw std::invalid_argument(wrong->message());
  if (!orbit.converged() || !(orbit.period > 0.0))
    throw std::invalid_argument("a convergence certificate needs a converged periodic orbit");
  point_ = orbit.state0;
  period_ = orbit.period;
  rate_ = orbit.floquet.max_modulus;
  eligible_ = orbit.floquet.stability == Stability::Stable &&
              rate_ < 1.0 - std::max(options_.margin, 10.0 * orbit.floquet.trivial_error);
  // The amplitude of each state over one period, sampled at 400 points (a range to 1e-5
  // relative for a smooth orbit).
  const int n = system.dimension();
  Eigen::VectorXd low = point_, high = point_;
  std::vector<double> times(401);
  for (int i = 0; i <= 400; ++i) times[i] = period_ * i / 400.0;
  Flow flow(system);
  flow.sample(point_, parameters_, 0.0, times, [&](double, const Eigen::VectorXd& z) {
    low = low.cwiseMin(z);
    high = high.cwiseMax(z);
  });
  scale_ = 0.5 * (high - low);
  const double largest = scale_.maxCoeff();
  for (int i = 0; i < n; ++i) scale_[i] = std::max(scale_[i], 1e-3 * largest);
  Eigen::VectorXd f(n);
  system.rhs(0.0, point_.data(), parameters_.data(), f.data());
  normal_ = f.cwiseQuotient(scale_);
  normal_.normalize();
}

double ConvergenceCertificate::side(const Eigen::VectorXd& z) const {
  return normal_.dot((z - point_).cwiseQuotient(scale_));
}

double ConvergenceCertificate::distance(const Eigen::VectorXd& z) const {
  return (z - point_).cwiseQuotient(scale_).lpNorm<Eigen::Infinity>();
}

bool ConvergenceCertificate::add(double t, const Eigen::VectorXd& z) {
  if (certified_) return true;
  const double g = side(z);
  const bool crossed = has_previous_ && g_previous_ < 0.0 && g >= 0.0;
  // Only near z*: the hyperplane is crossed far from the orbit too. Half the orbit's amplitude
  // is well beyond the certificate's radius and well short of the orbit's other side.
  if (crossed && std::min(distance(z_previous_), distance(z)) < 0.5) {
    // Cubic Hermite between the two samples, f at both; the crossing by regula falsi on it.
    const int n = system_.dimension();
    Eigen::VectorXd f0(n), f1(n);
    system_.rhs(t_previous_, z_previous_.data(), parameters_.data(), f0.data());
    system_.rhs(t, z.data(), parameters_.data(), f1.data());
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
    distances_.push_back(distance(at(s)));
    const int m = options_.returns;
    const std::size_t k = distances_.size();
    if (eligible_ && k > static_cast<std::size_t>(m)) {
      bool near = true;
      for (std::size_t j = k - m - 1; j < k; ++j) {
        near = near && distances_[j] < options_.radius;
        if (j > k - m - 1)
          near = near && std::abs(times_[j] - times_[j - 1] - period_) <= 0.05 * period_;
      }
      const double first = distances_[k - m - 1], last = distances_[k - 1];
      certified_ = near && (first == 0.0 || last <= std::pow(rate_, 0.5 * m) * first);
    }
  }
  has_previous_ = true;
  t_previous_ = t;
  g_previous_ = g;
  z_previous_ = z;
  return certified_;
}

}  // namespace sympathy
