#include "curve_system.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <Eigen/Eigenvalues>

namespace sympathy::detail {

namespace {

// Difference step in the scaled norm: g carries the monodromy's error of about 1e-9, so its
// differences are good to about 1e-4, enough for a chord that only has to converge. On fold
// curves forward differences at this step left plp's fold-of-cycles locus a Jacobian 17% off (its
// chord contracting by 0.17 an iteration: 9-10 iterations a point, steps kept small, 200 points
// short of AUTO's stops); central ones, two monodromies a column, converge in 3-5 and reach them
// in 0.6 s.
constexpr double kDifferenceStep = 1e-5;
// A corrected point: the scaled Newton step below this. The chord contracts by about a tenth
// per step, so the point is then within about 1e-9 of the curve in the scaled norm (the first
// parameter by its window's width: 1e-7 N/m on the k-branch's 1-100 N/m, 2e-9 relative) ...
constexpr double kStepTolerance = 1e-8;
// ... or, where the integration's noise stops the chord contracting, below this.
constexpr double kNoiseStep = 1e-7;
// How near the curve a corrected point lies in the scaled norm (after kStepTolerance): the floor
// of every point's uncertainty.
constexpr double kCorrectedPoint = 1e-9;
// The monodromy noise up to which the four constants above hold (CurveSystem::measure_noise):
// set for the default preset's 1e-9 to 2e-9, they still served the fast preset's 1.4e-8 (rtol
// 1e-8) on the anti-phase BP curve and failed from 2e-8 on. Scaled below 1e-8 they would only
// loosen the default's points (at 1.6e-9 the NS curve's end at c = 0 moved by 2.5e-7 N/m, away
// from the one-parameter branch's NS there).
constexpr double kTunedNoise = 1e-8;
// The least noise a central difference's step assumes: a monodromy's rounding (1e-12 relative
// gives a step of 4.6e-7 scaled).
constexpr double kLeastNoise = 1e-12;

// "1.2e-07": a scaled step for a message.
std::string scientific(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.2g", v);
  return buffer;
}

ShootingOptions single_shooting(ShootingOptions o) {
  // The curve needs the monodromy of one period; multiple shooting would add nothing here.
  o.segments = 1;
  return o;
}

}  // namespace

CurveSystem::CurveSystem(const OdeSystem& system, BifurcationType kind,
                         const InvariantSubspace& subspace, CriticalBlock block, int first,
                         int second, ParameterValues base, const CurveOptions& options)
    : system_(system),
      kind_(kind),
      subspace_(subspace),
      block_(block),
      first_(first),
      second_(second),
      base_(std::move(base)),
      options_(options),
      problem_(system, single_shooting(options.orbit.shooting)),
      n_(system.dimension()) {
  if (subspace.is_whole_space()) {
    v_ = Eigen::MatrixXd::Identity(n_, n_);
    c_.resize(n_, 0);
  } else {
    const auto bases = subspace.bases(n_);
    v_ = bases.inside;
    c_ = bases.across;
  }
  m_ = static_cast<int>(v_.cols());
  const long size = block == CriticalBlock::Across ? c_.cols() : v_.cols();
  if (kind == BifurcationType::NeimarkSacker && size < 2)
    throw std::invalid_argument("NS curve: the critical block has fewer than two dimensions");
  if (size < 1) throw std::invalid_argument("curve: the critical block is empty");
  tolerance_ = options.tolerance;  // until set_scales knows the state's size
}

ParameterValues CurveSystem::values(const Eigen::VectorXd& u) const {
  return system_.with_parameter(system_.with_parameter(base_, first_, u[m_ + 1]), second_,
                                u[m_ + 2]);
}

Eigen::VectorXd CurveSystem::unknowns_of(const Eigen::VectorXd& z0, double period, double p1,
                                         double p2) const {
  Eigen::VectorXd u(m_ + 3);
  u.head(m_) = v_.transpose() * z0;
  u[m_] = period;
  u[m_ + 1] = p1;
  u[m_ + 2] = p2;
  return u;
}

void CurveSystem::set_scales(const Eigen::VectorXd& u) {
  weights_.resize(m_ + 3);
  const double size = std::max(u.head(m_).cwiseAbs().maxCoeff(), 1e-12);
  weights_.head(m_).setConstant(1.0 / size);
  // As the branch's corrector: no integration's residual goes much below 20 rtol of the state's
  // size (1e-9 at the default preset; 2e-7 at the fast one, whose curve otherwise never counted
  // a stalled chord as converged at rtol 3e-8).
  tolerance_ = attainable_tolerance(options_.tolerance, options_.orbit.newton.rtol_factor,
                                    options_.orbit.shooting.flow, size);
  weights_[m_] = 1.0 / u[m_];
  weights_[m_ + 1] = 1.0 / (options_.first_upper - options_.first_lower);
  weights_[m_ + 2] = 1.0 / (options_.second_upper - options_.second_lower);
}

void CurveSystem::set_section(const Eigen::VectorXd& u) {
  y_section_ = u.head(m_);
  const Eigen::VectorXd f = v_.transpose() * system_.rhs(0.0, state(u), values(u));
  normal_ = f / std::max(f.norm(), 1e-300);
}

void CurveSystem::measure_noise(const Eigen::VectorXd& u, const Evaluation& e) {
  const Eigen::VectorXd z0 = state(u);
  const Eigen::VectorXd f0 = system_.rhs(0.0, z0, values(u));
  const double size = f0.norm();
  noise_ = size > 0.0 ? (e.monodromy * f0 - e.end_rate).norm() / size : 0.0;
  if (!std::isfinite(noise_)) noise_ = 0.0;
}

double CurveSystem::noise_factor() const {
  return std::max(1.0, noise_ / kTunedNoise);
}

Eigen::MatrixXd CurveSystem::block(const Evaluation& e) const {
  if (block_ == CriticalBlock::Across) return c_.transpose() * e.monodromy * c_;
  return v_.transpose() * e.monodromy * v_;
}

Eigen::MatrixXd CurveSystem::critical_matrix(const Evaluation& e) const {
  if (block_ == CriticalBlock::Shooting) {
    Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m_ + 1, m_ + 1);
    a.topLeftCorner(m_, m_) = v_.transpose() * e.monodromy * v_ - Eigen::MatrixXd::Identity(m_, m_);
    a.topRightCorner(m_, 1) = v_.transpose() * e.end_rate;
    a.bottomLeftCorner(1, m_) = normal_.transpose();
    return a;
  }
  const Eigen::MatrixXd b = block(e);
  const auto q = b.rows();
  switch (kind_) {
    case BifurcationType::PeriodDoubling:
      return b + Eigen::MatrixXd::Identity(q, q);
    case BifurcationType::NeimarkSacker: {
      const Eigen::MatrixXd c = exterior_square(b);
      return c - Eigen::MatrixXd::Identity(c.rows(), c.cols());
    }
    default:
      return b - Eigen::MatrixXd::Identity(q, q);
  }
}

void CurveSystem::assemble(const Eigen::VectorXd& u, Evaluation& e) const {
  e.residual.resize(m_ + 2);
  e.residual.head(m_) = v_.transpose() * e.end - u.head(m_);
  e.residual[m_] = normal_.dot(u.head(m_) - y_section_);
  e.test = borders_->value(critical_matrix(e));
  e.residual[m_ + 1] = e.test.g;
}

CurveSystem::Evaluation CurveSystem::evaluate(const Eigen::VectorXd& u) {
  Evaluation e;
  if (!u.allFinite() || !(u[m_] > 0.0)) {
    e.failure = "the unknowns left the domain (period not positive or not finite)";
    return e;
  }
  Eigen::VectorXd x(n_ + 1);
  x << state(u), u[m_];
  try {
    const ParameterValues p = values(u);
    system_.check_parameters(p);
    // No phase row (an empty section): the curve has its own, in y.
    const auto s = problem_.evaluate(x, p, PhaseSection{}, true);
    ++evaluations_;
    e.end = s.residual.head(n_) + x.head(n_);
    e.monodromy = s.transitions.front();
    e.end_rate = s.end_rates.front();
  } catch (const std::exception& ex) {
    e.failure = ex.what();
    return e;
  }
  if (!borders_) borders_.emplace(critical_matrix(e));
  assemble(u, e);
  e.ok = e.residual.allFinite();
  if (!e.ok) e.failure = "the test function is not finite";
  return e;
}

std::optional<Eigen::MatrixXd> CurveSystem::jacobian(const Eigen::VectorXd& u,
                                                     const Evaluation& e) {
  const int rows = m_ + 2, cols = m_ + 3;
  Eigen::MatrixXd j = Eigen::MatrixXd::Zero(rows, cols);
  // Shooting rows in y and T from the sensitivities; the phase row is linear.
  j.topLeftCorner(m_, m_) = v_.transpose() * e.monodromy * v_ - Eigen::MatrixXd::Identity(m_, m_);
  j.block(0, m_, m_, 1) = v_.transpose() * e.end_rate;
  j.block(m_, 0, 1, m_) = normal_.transpose();
  // Central differences on fold and PD curves (see kDifferenceStep); forward ones elsewhere: on
  // BP curves central ones lost the BP parabola's turn and the start at a 1:1 resonance
  // (bifurcation_curve_test), which is not understood yet.
  const bool central = kind_ == BifurcationType::Fold || kind_ == BifurcationType::PeriodDoubling;
  // A forward difference errs by its truncation, ~h, plus the noise over h: least where h grows
  // as the noise's square root. A central one's truncation is ~h^2: its step goes as the noise's
  // cube root, both kDifferenceStep at kTunedNoise. On AUTO's pen (noise 1.2e-11, central step
  // 1.1e-6) the PD curve reaches T = 30 (AUTO's UZSTOP) in 167 points; at 1e-5 the truncation
  // grew with the period's monodromy (|M| 1e8 at T 25), the chord took 7-8 iterations a point
  // and the curve ended at its 200-point limit at T 28.8 (forward differences: T 19.9).
  const double scale =
      central ? std::cbrt(std::max(noise_, kLeastNoise) / kTunedNoise) : std::sqrt(noise_factor());
  for (int c = 0; c < cols; ++c) {
    const double h = kDifferenceStep * scale / weights_[c];
    Eigen::VectorXd up = u;
    up[c] += h;
    const Evaluation du = evaluate(up);
    if (!du.ok) return std::nullopt;
    Eigen::VectorXd column;
    if (central) {
      Eigen::VectorXd down = u;
      down[c] -= h;
      const Evaluation dd = evaluate(down);
      if (!dd.ok) return std::nullopt;
      column = (du.residual - dd.residual) / (2 * h);
    } else {
      column = (du.residual - e.residual) / h;
    }
    j(rows - 1, c) = column[rows - 1];
    if (c > m_) j.block(0, c, m_, 1) = column.head(m_);
  }
  return j;
}

double CurveSystem::dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const {
  return (a.cwiseProduct(weights_)).dot(b.cwiseProduct(weights_));
}

Eigen::VectorXd CurveSystem::tangent(const Eigen::MatrixXd& jacobian,
                                     const Eigen::VectorXd& previous, int direction) const {
  // The null vector in scaled variables, where the columns are comparable.
  const Eigen::MatrixXd scaled = jacobian * weights_.cwiseInverse().asDiagonal();
  Eigen::MatrixXd square = Eigen::MatrixXd::Zero(scaled.cols(), scaled.cols());
  square.topRows(scaled.rows()) = scaled;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(square, Eigen::ComputeFullV);
  Eigen::VectorXd t = svd.matrixV().col(scaled.cols() - 1).cwiseQuotient(weights_);
  double orientation;
  if (previous.size() == t.size())
    orientation = dot(t, previous);
  else
    orientation = direction * (std::abs(t[m_ + 2]) > 1e-12 ? t[m_ + 2] : t[m_ + 1]);
  if (orientation < 0.0) t = -t;
  return t / norm(t);
}

CurveSystem::Correction CurveSystem::correct(Eigen::VectorXd guess, const Condition& condition,
                                             const Eigen::MatrixXd& jacobian) {
  Correction out;
  out.u = std::move(guess);
  const int size = m_ + 3;
  Eigen::MatrixXd full(size, size);
  full.topRows(size - 1) = jacobian;
  if (condition.index >= 0)
    full.row(size - 1) = Eigen::RowVectorXd::Unit(size, condition.index);
  else
    full.row(size - 1) = condition.tangent.cwiseProduct(weights_.cwiseAbs2()).transpose();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(full);
  const double step_tolerance = kStepTolerance * noise_factor();
  const double noise_step = kNoiseStep * noise_factor();
  double last_step = std::numeric_limits<double>::infinity();
  for (int it = 0; it <= options_.max_iterations; ++it) {
    out.evaluation = evaluate(out.u);
    out.iterations = it;
    if (!out.evaluation.ok) {
      out.reason = "integration failed: " + out.evaluation.failure;
      return out;
    }
    const bool small = shooting_residual(out.evaluation) <= tolerance_;
    if (it > 0 && small && last_step <= step_tolerance) {
      out.converged = true;
      return out;
    }
    Eigen::VectorXd f(size);
    f.head(size - 1) = out.evaluation.residual;
    f[size - 1] = condition.index >= 0
                      ? out.u[condition.index] - condition.value
                      : dot(condition.tangent, out.u - condition.from) - condition.step;
    const Eigen::VectorXd du = lu.solve(-f);
    const double step = norm(du);
    if (!std::isfinite(step)) {
      out.reason = "the chord step is not finite";
      return out;
    }
    // Stalled at the integration's noise: the step no longer contracts but is tiny.
    if (it > 0 && small && step <= noise_step && step > 0.5 * last_step) {
      out.converged = true;
      return out;
    }
    if (it > 1 && step > last_step) {
      out.reason = "the chord diverged (a step of " + scientific(step) + " after " +
                   scientific(last_step) + ", scaled; noise floor " + scientific(noise_step) + ")";
      return out;
    }
    out.u += du;
    last_step = step;
  }
  out.reason = "no convergence in " + std::to_string(options_.max_iterations) + " chord steps";
  return out;
}

void CurveSystem::update_borders(const Evaluation& e) {
  borders_->update(critical_matrix(e));
}

std::vector<std::complex<double>> CurveSystem::critical_multipliers(const Evaluation& e,
                                                                    bool* neutral) const {
  *neutral = false;
  const Eigen::MatrixXd b = block(e);
  const Eigen::VectorXcd mu = Eigen::EigenSolver<Eigen::MatrixXd>(b, false).eigenvalues();
  if (kind_ == BifurcationType::NeimarkSacker) {
    int bi = 0, bj = 1;
    double best = std::numeric_limits<double>::infinity();
    for (int i = 0; i < mu.size(); ++i)
      for (int j = i + 1; j < mu.size(); ++j)
        if (const double d = std::abs(mu[i] * mu[j] - 1.0); d < best) {
          best = d;
          bi = i;
          bj = j;
        }
    std::complex<double> a = mu[bi], c = mu[bj];
    if (a.imag() < c.imag()) std::swap(a, c);
    *neutral = std::abs(a.imag()) <= 1e-12 * std::abs(a);
    return {a, c};
  }
  const double target = kind_ == BifurcationType::PeriodDoubling ? -1.0 : 1.0;
  int best = 0;
  for (int i = 1; i < mu.size(); ++i)
    if (std::abs(mu[i] - target) < std::abs(mu[best] - target)) best = i;
  return {mu[best]};
}

CurvePoint CurveSystem::point(const Eigen::VectorXd& u, const Evaluation& e,
                              const Eigen::MatrixXd& jacobian,
                              const Eigen::VectorXd& tangent) const {
  CurvePoint p;
  p.first = u[m_ + 1];
  p.second = u[m_ + 2];
  p.period = u[m_];
  p.state0 = state(u);
  const ParameterValues values_here = values(u);
  p.floquet = analyze_floquet({e.monodromy}, system_.rhs(0.0, p.state0, values_here), {},
                              options_.orbit.floquet);
  if (!subspace_.is_whole_space()) label_symmetry(p.floquet, {e.monodromy}, v_, c_);
  if (kind_ == BifurcationType::Fold) {
    // At a fold the trivial multiplier's Jordan partner: the other one nearest to +1.
    int best = -1;
    for (int i = 0; i < static_cast<int>(p.floquet.multipliers.size()); ++i)
      if (i != p.floquet.trivial &&
          (best < 0 || std::abs(p.floquet.multipliers[i].value - 1.0) <
                           std::abs(p.floquet.multipliers[best].value - 1.0)))
        best = i;
    if (best >= 0) p.critical = {p.floquet.multipliers[best].value};
  } else {
    p.critical = critical_multipliers(e, &p.neutral_saddle);
  }
  if (kind_ == BifurcationType::NeimarkSacker && !p.neutral_saddle)
    p.rotation = std::abs(std::arg(p.critical.front())) / (2.0 * M_PI);
  p.test = e.test.g;
  p.residual = shooting_residual(e);
  // The first parameter's uncertainty at a fixed second: along the one-parameter branch there
  // (the null vector of the shooting and phase rows over y, T, p1), g moves at dg/dp1; an error
  // d of the critical multiplier moves g by d |w^T v| (twice that for |mu|^2 on an NS curve).
  const Eigen::MatrixXd rows = jacobian.topLeftCorner(m_ + 1, m_ + 2);
  Eigen::MatrixXd square = Eigen::MatrixXd::Zero(m_ + 2, m_ + 2);
  square.topRows(m_ + 1) = rows * weights_.head(m_ + 2).cwiseInverse().asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(square, Eigen::ComputeFullV);
  const Eigen::VectorXd t1 = svd.matrixV().col(m_ + 1).cwiseQuotient(weights_.head(m_ + 2));
  const double speed = std::abs(jacobian.row(m_ + 1).head(m_ + 2).dot(t1) / t1[m_ + 1]);
  const double error = p.floquet.trivial_error * (kind_ == BifurcationType::NeimarkSacker ? 2 : 1);
  p.uncertainty = speed > 0.0 && std::abs(t1[m_ + 1]) > 0.0
                      ? error * e.test.eigenvalue_rate() / speed
                      : std::numeric_limits<double>::infinity();
  // At least what the corrector leaves: about 1e-9 of the first parameter's window (see
  // kStepTolerance). On an LP curve the one-parameter branch turns at the point, t1's parameter
  // component vanishes and the quotient above with it (1e-22 on abc's fold curve).
  p.uncertainty = std::max(p.uncertainty, kCorrectedPoint * noise_factor() / weights_[m_ + 1]);
  p.unknowns = u;
  p.tangent = tangent;
  return p;
}

std::vector<int> CurveSystem::other_indices(const CurvePoint& p) const {
  std::vector<int> rest;
  for (int i = 0; i < static_cast<int>(p.floquet.multipliers.size()); ++i)
    if (i != p.floquet.trivial) rest.push_back(i);
  const auto value = [&](int i) { return p.floquet.multipliers[i].value; };
  for (const auto& c : p.critical) {
    if (rest.empty()) break;
    const auto nearest = std::min_element(rest.begin(), rest.end(), [&](int a, int b) {
      return std::abs(value(a) - c) < std::abs(value(b) - c);
    });
    rest.erase(nearest);
  }
  return rest;
}

std::vector<std::complex<double>> CurveSystem::others(const CurvePoint& p) const {
  std::vector<std::complex<double>> rest;
  for (int i : other_indices(p)) rest.push_back(p.floquet.multipliers[i].value);
  return rest;
}

}  // namespace sympathy::detail
