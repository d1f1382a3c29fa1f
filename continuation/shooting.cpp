#include "sympathy/continuation/shooting.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace sympathy {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
}  // namespace

ShootingProblem::ShootingProblem(const OdeSystem& system, ShootingOptions options,
                                 double forced_period)
    : system_(system),
      options_(options),
      n_(system.dimension()),
      autonomous_(system.autonomous()),
      forced_period_(forced_period),
      flow_(system, options.flow) {
  if (options_.segments < 1) throw std::invalid_argument("shooting needs at least one segment");
  if (!autonomous_ && !(forced_period_ > 0.0))
    throw std::invalid_argument("a periodically forced system needs its period");
  z_ref_ = Eigen::VectorXd::Zero(n_);
  f_ref_ = Eigen::VectorXd::Zero(n_);
  winding_ = Eigen::VectorXd::Zero(n_);
}

void ShootingProblem::set_phase_reference(const Eigen::VectorXd& z_ref, const ParameterValues& p) {
  set_phase_section(z_ref, system_.rhs(0.0, z_ref, p));
}

void ShootingProblem::set_phase_section(const Eigen::VectorXd& z_ref,
                                        const Eigen::VectorXd& normal) {
  z_ref_ = z_ref;
  f_ref_ = normal;
}

double ShootingProblem::period(const Eigen::VectorXd& x) const {
  return autonomous_ ? x[n_ * options_.segments] : forced_period_;
}

Eigen::VectorXd ShootingProblem::unknowns_from(const Eigen::VectorXd& z0, const ParameterValues& p,
                                               double period) {
  const int m = options_.segments;
  Eigen::VectorXd x(unknowns());
  const double T = autonomous_ ? period : forced_period_;
  Eigen::VectorXd z = z0;
  for (int j = 0; j < m; ++j) {
    x.segment(j * n_, n_) = z;
    if (j + 1 < m) z = flow_.advance(z, p, j * T / m, (j + 1) * T / m);
  }
  if (autonomous_) x[n_ * m] = period;
  winding_.setZero();
  const std::vector<int> angles = system_.angle_states();
  if (!angles.empty()) {
    // The gain of each angle over the guess's period, to the nearest whole turn: a guess within
    // half a turn of an orbit winds as the orbit does.
    const Eigen::VectorXd end = flow_.advance(z, p, (m - 1) * T / m, T);
    for (int i : angles) winding_[i] = kTwoPi * std::round((end[i] - z0[i]) / kTwoPi);
  }
  return x;
}

FlowStatistics ShootingProblem::statistics() const {
  FlowStatistics s = flow_.statistics();
  if (plain_flow_) s += plain_flow_->statistics();
  return s;
}

void ShootingProblem::reset_statistics() {
  flow_.reset_statistics();
  if (plain_flow_) plain_flow_->reset_statistics();
}

Eigen::VectorXd ShootingProblem::residual(const Eigen::VectorXd& x, const ParameterValues& p) {
  if (!plain_flow_) {
    FlowOptions tight = options_.flow;
    // Not below 1e-13: CVODES reports tolerances near the unit roundoff as too much accuracy.
    tight.rtol = std::max(options_.flow.rtol / 100.0, std::min(options_.flow.rtol, 1e-13));
    tight.atol = options_.flow.atol / 10.0;
    plain_flow_ = std::make_unique<Flow>(system_, tight);
  }
  return evaluate(x, p, false, -1, *plain_flow_).residual;
}

ShootingProblem::Evaluation ShootingProblem::evaluate(const Eigen::VectorXd& x,
                                                      const ParameterValues& p, bool derivatives,
                                                      int parameter) {
  return evaluate(x, p, derivatives, parameter, flow_);
}

ShootingProblem::Evaluation ShootingProblem::evaluate(const Eigen::VectorXd& x,
                                                      const ParameterValues& p, bool derivatives,
                                                      int parameter, Flow& flow) {
  const int m = options_.segments;
  const double T = period(x);
  if (!(T > 0.0)) throw IntegrationError("shooting: the period is not positive", 0.0);
  Evaluation e;
  e.parameters = p;
  e.derivatives = derivatives;
  e.parameter = parameter;
  e.residual.resize(unknowns());
  if (parameter >= 0) e.parameter_sensitivities.resize(n_, m);
  const std::vector<int> parameters =
      parameter >= 0 ? std::vector<int>{parameter} : std::vector<int>{};
  const bool sampled = derivatives && record_samples_;
  constexpr int intervals = PeriodSamples::intervals;
  if (sampled) {
    e.samples.period = T;
    e.samples.states.resize(n_, intervals + 1);
  }
  for (int j = 0; j < m; ++j) {
    const Eigen::VectorXd zj = x.segment(j * n_, n_);
    // Autonomous segments all start at t = 0; forced ones at their place in the period.
    const double t0 = autonomous_ ? 0.0 : j * T / m;
    const double t1 = autonomous_ ? T / m : (j + 1) * T / m;
    // The samples in this segment (the last one's end included), in its own time.
    std::vector<double> times;
    int first = 0;
    if (sampled) {
      first = (j * intervals + m - 1) / m;  // the first k with T k / intervals >= j T / m
      const int last = j + 1 == m ? intervals : ((j + 1) * intervals + m - 1) / m - 1;
      const double offset = autonomous_ ? j * T / m : 0.0;
      for (int k = first; k <= last; ++k)
        times.push_back(std::clamp(T * k / intervals - offset, t0, t1));
    }
    Eigen::VectorXd end;
    if (derivatives) {
      int k = first;
      auto d = flow.advance_with_sensitivities(
          zj, p, t0, t1, true, parameters, times,
          [&](double, const Eigen::VectorXd& z) { e.samples.states.col(k++) = z; });
      end = std::move(d.state);
      e.transitions.push_back(std::move(d.transition));
      if (parameter >= 0) e.parameter_sensitivities.col(j) = d.parameter_sensitivities.col(0);
      e.end_rates.push_back(system_.rhs(t1, end, p));
    } else {
      end = flow.advance(zj, p, t0, t1);
    }
    e.residual.segment(j * n_, n_) = end - x.segment(((j + 1) % m) * n_, n_);
    if (j + 1 == m) e.residual.segment(j * n_, n_) -= winding_;
  }
  if (autonomous_) e.residual[n_ * m] = f_ref_.dot(x.head(n_) - z_ref_);
  return e;
}

Eigen::SparseMatrix<double> ShootingProblem::jacobian(const Evaluation& e,
                                                      bool parameter_column) const {
  if (!e.derivatives)
    throw std::logic_error("shooting Jacobian needs an evaluation with derivatives");
  if (parameter_column && e.parameter < 0)
    throw std::logic_error("shooting Jacobian: the evaluation has no parameter sensitivity");
  const int m = options_.segments;
  const int rows = unknowns();
  const int cols = rows + (parameter_column ? 1 : 0);
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(m) * (n_ * n_ + 3 * n_) + n_);
  for (int j = 0; j < m; ++j) {
    const int r0 = j * n_;
    const int next = ((j + 1) % m) * n_;
    for (int c = 0; c < n_; ++c)
      for (int r = 0; r < n_; ++r) t.emplace_back(r0 + r, r0 + c, e.transitions[j](r, c));
    for (int i = 0; i < n_; ++i) t.emplace_back(r0 + i, next + i, -1.0);
    if (autonomous_)
      for (int i = 0; i < n_; ++i) t.emplace_back(r0 + i, n_ * m, e.end_rates[j][i] / m);
    if (parameter_column)
      for (int i = 0; i < n_; ++i) t.emplace_back(r0 + i, rows, e.parameter_sensitivities(i, j));
  }
  if (autonomous_)
    for (int i = 0; i < n_; ++i) t.emplace_back(n_ * m, i, f_ref_[i]);
  Eigen::SparseMatrix<double> jac(rows, cols);
  jac.setFromTriplets(t.begin(), t.end());  // duplicates (M - I with one segment) are summed
  return jac;
}

}  // namespace sympathy
