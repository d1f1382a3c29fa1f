#include "sympathy/continuation/branch_space.hpp"

#include <cmath>
#include <utility>

namespace sympathy {

BranchSpace::BranchSpace(const OdeSystem& system, const ShootingProblem& problem, int parameter,
                         ParameterValues base, double range, double rank_tolerance)
    : system_(system),
      parameter_(parameter),
      base_(std::move(base)),
      range_(range),
      n_(problem.dimension()),
      m_(problem.segments()),
      unknowns_(problem.unknowns()) {
  linear_.prefer_sparse = m_ > 1;
  linear_.rank_tolerance = rank_tolerance;
}

ParameterValues BranchSpace::values_at(double v) const {
  return system_.with_parameter(base_, parameter_, v);
}

void BranchSpace::reset_scales(const Eigen::VectorXd& z0, double period, const FlowOptions& flow,
                               const PeriodSamples* samples) {
  weights_.resize(unknowns_ + 1);
  sizes_.resize(0);
  widen_scales(z0, base_, period, flow, samples);
  weights_[n_ * m_] = 1.0 / period;
  weights_[unknowns_] = 1.0 / range_;
}

void BranchSpace::widen_scales(const Eigen::VectorXd& z0, const ParameterValues& p, double period,
                               const FlowOptions& flow_options, const PeriodSamples* samples) {
  Eigen::VectorXd size = z0.cwiseAbs();
  constexpr int every = PeriodSamples::intervals / 100;
  static_assert(every * 100 == PeriodSamples::intervals);
  if (samples && samples->of(z0, period)) {
    for (int k = 1; k <= 100; ++k) size = size.cwiseMax(samples->states.col(every * k).cwiseAbs());
    include_sizes(size);
    return;
  }
  Flow flow(system_, flow_options);
  std::vector<double> times;
  for (int k = 1; k <= 100; ++k) times.push_back(period * k / 100.0);
  flow.sample(z0, p, 0.0, times,
              [&](double, const Eigen::VectorXd& z) { size = size.cwiseMax(z.cwiseAbs()); });
  include_sizes(size);
}

void BranchSpace::include_sizes(const Eigen::VectorXd& size) {
  sizes_ = sizes_.size() ? Eigen::VectorXd(sizes_.cwiseMax(size)) : size;
  const double floor = std::max(1e-3 * sizes_.maxCoeff(), 1e-12);
  for (int j = 0; j < m_; ++j)
    for (int i = 0; i < n_; ++i)
      weights_[j * n_ + i] =
          1.0 / (std::max(sizes_[i], floor) * std::sqrt(static_cast<double>(m_)));
}

double BranchSpace::dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
  return (weights_.array().square() * u.array() * v.array()).sum();
}

Eigen::VectorXd BranchSpace::arclength_row(const Eigen::VectorXd& tangent) const {
  return weights_.array().square() * tangent.array();
}

// In units of the orbits' sizes an oscillation is nearly circular, and a section normal to the
// flow there contains the directions in which its amplitude changes, so that the points do not
// slide along the orbits as the branch goes on (in raw units the normal is dominated by the large
// rates of the velocities, and the section is nearly a level of one velocity, which a shrinking
// swing leaves).
PhaseSection BranchSpace::section(const Eigen::VectorXd& z, double v) const {
  const Eigen::VectorXd w = weights_.head(n_);
  return {z, w.array().square() * system_.rhs(0.0, z, values_at(v)).array()};
}

// The direction of a shift in time along the orbits at y: f at each segment's state, nothing in
// the period or the parameter. Sections and phase drift move tangents along it without any change
// of orbit.
Eigen::VectorXd BranchSpace::time_shift(const Eigen::VectorXd& y) const {
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(y.size());
  // A forced system's orbits are fixed in time by the forcing: no shift leaves them alone.
  if (!system_.autonomous()) return phi;
  const ParameterValues p = values_at(y[unknowns_]);
  for (int j = 0; j < m_; ++j) phi.segment(j * n_, n_) = system_.rhs(0.0, y.segment(j * n_, n_), p);
  return phi;
}

double BranchSpace::orbit_cosine(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                 const Eigen::VectorXd& at) const {
  const Eigen::VectorXd phi = time_shift(at);
  const double pp = dot(phi, phi);
  auto strip = [&](const Eigen::VectorXd& x) {
    return pp > 0.0 ? Eigen::VectorXd(x - dot(x, phi) / pp * phi) : x;
  };
  const Eigen::VectorXd a = strip(u), b = strip(v);
  const double norms = std::sqrt(dot(a, a) * dot(b, b));
  return norms > 0.0 ? dot(a, b) / norms : 0.0;
}

double BranchSpace::turn_cosine(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                const Eigen::VectorXd& at) const {
  // The orbit is (z_0, T, p); the later segments' starts follow from it. With equal-time
  // segments they slide along an orbit whose shape changes and turn with the growth inside the
  // segments (through the spike of AUTO's ab at p2 = 16, growth 1e3-1e4 per segment on 4
  // segments, the whole tangent turned past the limit at every step: 146 turns, steps down to
  // 1e-4, the point limit reached at p1 = 0.172 of 0.25), so they are left out, as is the shift
  // in time along the orbit at z_0.
  const Eigen::VectorXd phi = time_shift(at);
  auto orbit_part = [&](const Eigen::VectorXd& x) {
    Eigen::VectorXd y = x;
    y.segment(n_, (m_ - 1) * n_).setZero();
    const auto w2 = weights_.head(n_).array().square();
    const auto f = phi.head(n_).array();
    const double ff = (w2 * f * f).sum();
    if (ff > 0.0) y.head(n_) -= ((w2 * f * x.head(n_).array()).sum() / ff) * phi.head(n_);
    return y;
  };
  const Eigen::VectorXd a = orbit_part(u), b = orbit_part(v);
  const double norms = std::sqrt(dot(a, a) * dot(b, b));
  return norms > 0.0 ? dot(a, b) / norms : 0.0;
}

Eigen::VectorXd BranchSpace::tangent(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& y,
                                     const Eigen::VectorXd& previous) const {
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(unknowns_ + 1);
  rhs[unknowns_] = 1.0;
  Eigen::VectorXd tau = solve_linear(bordered(jacobian, arclength_row(previous)), rhs, linear_).x;
  tau /= std::sqrt(dot(tau, tau));
  if (orbit_cosine(tau, previous, y) < 0.0) tau = -tau;
  return tau;
}

Eigen::SparseMatrix<double> bordered(const Eigen::SparseMatrix<double>& jac,
                                     const Eigen::VectorXd& row) {
  const int N = static_cast<int>(jac.rows());
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(jac.nonZeros() + N + 1);
  for (int k = 0; k < jac.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator i(jac, k); i; ++i)
      t.emplace_back(static_cast<int>(i.row()), static_cast<int>(i.col()), i.value());
  for (int k = 0; k <= N; ++k)
    if (row[k] != 0.0) t.emplace_back(N, k, row[k]);
  Eigen::SparseMatrix<double> b(N + 1, N + 1);
  b.setFromTriplets(t.begin(), t.end());
  return b;
}

}  // namespace sympathy
