#include "sympathy/continuation/shooting.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <functional>
#include <numbers>
#include <random>
#include <stdexcept>
#include <thread>
#include <utility>

#include "sympathy/core/across_variations.hpp"
#include "sympathy/core/reduced_system.hpp"

namespace sympathy {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
// Every how many of the period's samples the restricted field and its Jacobian are compared with
// the remembered ones (use_symmetry): 41 of 801, a tenth of a plain period's cost.
constexpr int kFieldCheckStride = 20;
// How much looser a coarse plain run is (ShootingProblem::residual).
constexpr double kCoarse = 1e3;

// Where f's symmetry is probed around a state: its own size per component, at least a tenth of
// its largest (a component that is zero at this point is not zero on the orbit).
Eigen::VectorXd probe_scale(const Eigen::VectorXd& z) {
  const double largest = std::max(z.cwiseAbs().maxCoeff(), 1e-300);
  return z.cwiseAbs().cwiseMax(0.1 * largest);
}

// equivariance_defect's test for df/dp: dfdp(g z) = g dfdp(z) at random points of that size.
double parameter_equivariance_defect(
    const OdeSystem& system, const ParameterValues& p, int parameter, const Eigen::VectorXd& scale,
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g) {
  const int n = system.dimension();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  Eigen::VectorXd z(n), dfdp(n), at_gz(n);
  for (int trial = 0; trial < 3; ++trial) {
    for (int i = 0; i < n; ++i) z[i] = scale[i] * u(rng);
    system.parameter_derivative(0.0, z.data(), p.data(), parameter, dfdp.data());
    const Eigen::VectorXd gz = g(z);
    system.parameter_derivative(0.0, gz.data(), p.data(), parameter, at_gz.data());
    const double norm = std::max(dfdp.cwiseAbs().maxCoeff(), 1e-300);
    worst = std::max(worst, (at_gz - g(dfdp)).cwiseAbs().maxCoeff() / norm);
  }
  return worst;
}
}  // namespace

// The last full evaluation with derivatives of an orbit in a reflection's fixed space V, and what
// reusing it needs (shooting.hpp).
struct ShootingProblem::SymmetricOrbit {
  SymmetricOrbit(const OdeSystem& system, const InvariantSubspace& subspace_, Reflection g,
                 const FlowOptions& options)
      : subspace(subspace_),
        reflection(std::move(g)),
        across(system, subspace_),
        flow(across, options),
        inside(subspace_.bases(system.dimension()).inside),
        embedding(across.coordinates().embedding()),
        reading(across.coordinates().restriction() * inside * inside.transpose()) {}
  InvariantSubspace subspace;
  Reflection reflection;
  AcrossVariations across;
  Flow flow;                                // plain runs of `across`
  Eigen::MatrixXd inside;                   // an orthonormal basis of V
  Eigen::MatrixXd embedding;                // P: z = P y for y V's coordinates
  Eigen::MatrixXd reading;                  // R Pi_V: the coordinates of a vector's part in V
  std::unique_ptr<AcrossVariations> split;  // with V's block and a parameter column
  std::unique_ptr<Flow> split_flow;         // plain runs of `split`
  std::unique_ptr<ReducedSystem> reduced;   // the orbit alone in V (residual)
  std::unique_ptr<Flow> reduced_flows[2];   // tightened as plain_flows_
  int served = 0;                           // evaluations served by the across block alone
  int split_served = 0;                     // by split_evaluation
  bool known = false;                       // the remembered full evaluation:
  Eigen::VectorXd x;                        // its unknowns
  Evaluation evaluation;                    // itself
  Eigen::MatrixXd block;                    // V's block of its monodromy, inside^T Phi inside
  Eigen::VectorXd scale;                    // the orbit's largest amplitude per component
  std::vector<Eigen::VectorXd> field;       // R f at every kFieldCheckStride-th sample
  std::vector<Eigen::MatrixXd> jacobians;   // R J P there
};

ShootingProblem::~ShootingProblem() = default;

void ShootingProblem::use_symmetry(const InvariantSubspace& subspace) {
  symmetric_.reset();
  if (subspace.is_whole_space()) return;
  // The symmetric evaluations integrate variational equations appended to the state in plain runs,
  // which carry no saltation matrix across a switching surface: a piecewise-smooth system's orbits
  // get the whole computation, whose flow does.
  if (system_.switching_count() > 0) return;
  if (auto g = subspace.reflection(n_))
    symmetric_ = std::make_unique<SymmetricOrbit>(system_, subspace, std::move(*g), options_.flow);
}

int ShootingProblem::across_evaluations() const {
  return symmetric_ ? symmetric_->served : 0;
}

int ShootingProblem::split_evaluations() const {
  return symmetric_ ? symmetric_->split_served : 0;
}

void ShootingProblem::remember(const Eigen::VectorXd& x, const Evaluation& e) {
  SymmetricOrbit& s = *symmetric_;
  s.known = false;
  const Eigen::VectorXd z0 = x.head(n_);
  const double size = std::max(1.0, z0.cwiseAbs().maxCoeff());
  if ((z0 - s.subspace.project(z0)).cwiseAbs().maxCoeff() > 1e-13 * size) return;
  if (!e.samples.of(z0, period(x))) return;
  s.x = x;
  s.evaluation = e;
  s.block = s.inside.transpose() * e.transitions[0] * s.inside;
  s.scale = e.samples.states.cwiseAbs().rowwise().maxCoeff();
  // Components that stay zero on V (the platform) are probed off V at the orbit's own size.
  const double largest = std::max(s.scale.maxCoeff(), 1e-300);
  for (int i = 0; i < n_; ++i) s.scale[i] = std::max(s.scale[i], 0.1 * largest);
  s.field.clear();
  s.jacobians.clear();
  const ReducedSystem reduced(system_, s.subspace);
  for (int k = 0; k <= PeriodSamples::intervals; k += kFieldCheckStride) {
    const Eigen::VectorXd y = s.across.coordinates().restrict(e.samples.states.col(k));
    s.field.push_back(reduced.rhs(0.0, y, e.parameters));
    s.jacobians.push_back(reduced.jacobian(0.0, y, e.parameters));
  }
  s.known = true;
}

std::optional<ShootingProblem::Evaluation> ShootingProblem::across_evaluation(
    const Eigen::VectorXd& x, const ParameterValues& p, int parameter) {
  SymmetricOrbit& s = *symmetric_;
  if (!s.known || parameter != s.evaluation.parameter) return std::nullopt;
  const Eigen::VectorXd dx = x - s.x;
  if (dx.cwiseAbs().maxCoeff() > 1e-10 * std::max(1.0, s.x.cwiseAbs().maxCoeff()))
    return std::nullopt;
  // f keeps the reflection at p.
  const Reflection& g = s.reflection;
  if (!(equivariance_defect(system_, p, s.scale,
                            [&](const Eigen::VectorXd& z) { return g.apply(z); }) <= 1e-12))
    return std::nullopt;
  // The restricted field does not move with the parameter along the orbit: at every
  // kFieldCheckStride-th sample its derivative is exactly zero, and it and its Jacobian are the
  // remembered ones (the derivative at all 801 samples was 6% of the fast preset's instructions on
  // the anti-phase branch; the orbit integrated below must close as the remembered one did, too).
  const ReducedSystem reduced(system_, s.subspace);
  const auto& coordinates = s.across.coordinates();
  const auto& states = s.evaluation.samples.states;
  if (parameter >= 0) {
    Eigen::VectorXd dfdp(reduced.dimension());
    for (int k = 0; k < states.cols(); k += kFieldCheckStride) {
      const Eigen::VectorXd y = coordinates.restrict(states.col(k));
      reduced.parameter_derivative(0.0, y.data(), p.data(), parameter, dfdp.data());
      if (dfdp.cwiseAbs().maxCoeff() != 0.0) return std::nullopt;
    }
  }
  for (int k = 0, j = 0; k < states.cols(); k += kFieldCheckStride, ++j) {
    const Eigen::VectorXd y = coordinates.restrict(states.col(k));
    if (reduced.rhs(0.0, y, p) != s.field[j] || reduced.jacobian(0.0, y, p) != s.jacobians[j])
      return std::nullopt;
  }
  // The orbit in V with W's block, over the remembered period.
  const Eigen::VectorXd z0 = s.x.head(n_);
  const double T = period(s.x);
  const Eigen::VectorXd w = s.flow.advance(s.across.start(z0), p, 0.0, T);
  const Eigen::VectorXd end = z0 + s.evaluation.residual.head(n_) + winding_;
  const Eigen::VectorXd y_end = w.head(s.across.inside());
  if ((y_end - coordinates.restrict(end)).cwiseAbs().maxCoeff() > 1e-7 * s.scale.maxCoeff())
    return std::nullopt;
  const Eigen::MatrixXd& C = s.across.breaking_basis();
  Evaluation e;
  e.parameters = p;
  e.derivatives = true;
  e.parameter = parameter;
  e.transitions.push_back(s.inside * s.block * s.inside.transpose() +
                          C * s.across.block(w) * C.transpose());
  e.end_rates.push_back(system_.rhs(T, end, p));
  if (parameter >= 0) e.parameter_sensitivities = Eigen::MatrixXd::Zero(n_, 1);
  // The remembered residual, to first order in the unknowns' difference (the phase condition's
  // row is the caller's section's: evaluate).
  e.residual = s.evaluation.residual;
  e.residual.head(n_) += (e.transitions[0] - Eigen::MatrixXd::Identity(n_, n_)) * dx.head(n_) +
                         e.end_rates[0] * dx[n_];
  if (dx.head(n_).cwiseAbs().maxCoeff() == 0.0 && dx[n_] == 0.0) e.samples = s.evaluation.samples;
  ++s.served;
  return e;
}

std::optional<Eigen::VectorXd> ShootingProblem::symmetric_part(const Eigen::VectorXd& z,
                                                               const ParameterValues& p) const {
  // The corrector's steps leave a branch in V only to rounding (~1e-16 of the state): within
  // 1e-13 of the state's size, as remember() asks, the state is taken as its part in V.
  const SymmetricOrbit& s = *symmetric_;
  Eigen::VectorXd zV = in_subspace(z);
  const double size = std::max(1.0, z.cwiseAbs().maxCoeff());
  if ((z - zV).cwiseAbs().maxCoeff() > 1e-13 * size) return std::nullopt;
  const Reflection& g = s.reflection;
  if (!(equivariance_defect(system_, p, probe_scale(z),
                            [&](const Eigen::VectorXd& v) { return g.apply(v); }) <= 1e-12))
    return std::nullopt;
  return zV;
}

bool ShootingProblem::keep_in_subspace(Eigen::VectorXd& unknowns, const ParameterValues& p) const {
  if (!symmetric_ || options_.segments != 1 || !autonomous_) return false;
  const auto zV = symmetric_part(unknowns.head(n_), p);
  if (!zV) return false;
  unknowns.head(n_) = *zV;
  return true;
}

void ShootingProblem::project_on_subspace(Eigen::VectorXd& direction) const {
  if (symmetric_) direction.head(n_) = in_subspace(direction.head(n_));
}

// The orthogonal projection onto V, then through V's coordinates: exactly in V (zeros exactly
// zero, the components tied to another exactly its signed copy), not only to rounding.
Eigen::VectorXd ShootingProblem::in_subspace(const Eigen::VectorXd& z) const {
  const auto& k = symmetric_->across.coordinates();
  return k.embed(k.restrict(symmetric_->subspace.project(z)));
}

std::optional<ShootingProblem::Evaluation> ShootingProblem::split_evaluation(
    const Eigen::VectorXd& x, const ParameterValues& p, int parameter) {
  SymmetricOrbit& s = *symmetric_;
  // The forward-sensitivity module stays what it is asked to be: the cross-check of the
  // augmented systems.
  if (options_.flow.sensitivities != Sensitivities::Augmented) return std::nullopt;
  const auto& k = s.across.coordinates();
  const Eigen::VectorXd z0 = x.head(n_);
  const auto zV = symmetric_part(z0, p);
  if (!zV) return std::nullopt;
  // df/dp keeps the reflection too (a parameter that detunes the symmetry, such as one
  // metronome's length, moves the orbit off V: its column has a part in W).
  const Reflection& g = s.reflection;
  if (parameter >= 0 && !(parameter_equivariance_defect(
                              system_, p, parameter, probe_scale(z0),
                              [&](const Eigen::VectorXd& z) { return g.apply(z); }) <= 1e-12))
    return std::nullopt;
  const double T = period(x);
  if (!(T > 0.0)) throw IntegrationError("shooting: the period is not positive", 0.0);
  if (!s.split || s.split->column_parameter() != parameter) {
    s.split_flow.reset();
    s.split = std::make_unique<AcrossVariations>(system_, s.subspace, true, parameter);
    s.split_flow = std::make_unique<Flow>(*s.split, options_.flow);
  }
  const AcrossVariations& split = *s.split;
  const int r = split.inside();
  Evaluation e;
  e.parameters = p;
  e.derivatives = true;
  e.parameter = parameter;
  Eigen::VectorXd w;
  if (record_samples_) {
    constexpr int intervals = PeriodSamples::intervals;
    std::vector<double> times(intervals + 1);
    for (int i = 0; i <= intervals; ++i) times[i] = T * i / intervals;
    e.samples.period = T;
    e.samples.states.resize(n_, intervals + 1);
    int i = 0;
    s.split_flow->sample(split.start(*zV), p, 0.0, times, [&](double, const Eigen::VectorXd& wi) {
      e.samples.states.col(i) = k.embed(wi.head(r));
      if (++i == intervals + 1) w = wi;
    });
    e.samples.states.col(0) = z0;  // within 1e-13 of *zV (symmetric_part)
  } else {
    w = s.split_flow->advance(split.start(*zV), p, 0.0, T);
  }
  const Eigen::VectorXd end = k.embed(w.head(r));
  const Eigen::MatrixXd& C = split.breaking_basis();
  e.transitions.push_back(s.embedding * split.inside_block(w) * s.reading +
                          C * split.block(w) * C.transpose());
  e.end_rates.push_back(system_.rhs(T, end, p));
  if (parameter >= 0) e.parameter_sensitivities = s.embedding * split.parameter_column(w);
  // At z0 itself, to first order in its part across V.
  e.residual.resize(unknowns());
  e.residual.head(n_) =
      end - *zV - winding_ + (e.transitions[0] - Eigen::MatrixXd::Identity(n_, n_)) * (z0 - *zV);
  e.residual[n_] = 0.0;  // the section's row: evaluate
  ++s.split_served;
  return e;
}

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
  winding_ = Eigen::VectorXd::Zero(n_);
}

PhaseSection ShootingProblem::section_through(const Eigen::VectorXd& z,
                                              const ParameterValues& p) const {
  return {z, system_.rhs(0.0, z, p)};
}

void ShootingProblem::move_to_section(Evaluation& e, const Eigen::VectorXd& x,
                                      PhaseSection section) const {
  if (autonomous_) e.residual[n_ * options_.segments] = section.offset(x.head(n_));
  e.section = std::move(section);
}

double ShootingProblem::period(const Eigen::VectorXd& x) const {
  return autonomous_ ? x[n_ * options_.segments] : forced_period_;
}

Eigen::VectorXd ShootingProblem::unknowns_from(const Eigen::VectorXd& z0, const ParameterValues& p,
                                               double period) {
  return unknowns_from_starts(Eigen::MatrixXd(z0), p, period);
}

Eigen::VectorXd ShootingProblem::unknowns_from_starts(const Eigen::MatrixXd& starts,
                                                      const ParameterValues& p, double period) {
  const int m = options_.segments, k = static_cast<int>(starts.cols());
  if (k < 1 || m % k != 0 || starts.rows() != n_)
    throw std::invalid_argument("unknowns_from_starts: " + std::to_string(k) + " starts for " +
                                std::to_string(m) + " segments of " + std::to_string(n_) +
                                " states");
  Eigen::VectorXd x(unknowns());
  const double T = autonomous_ ? period : forced_period_;
  Eigen::VectorXd z;
  for (int j = 0; j < m; ++j) {
    // Segment j starts at j T / m: a given state where one is (column j k / m), else the previous
    // segment's start integrated over one segment.
    const int i = j * k / m;
    z = j * k % m == 0 ? Eigen::VectorXd(starts.col(i))
                       : flow_.advance(z, p, (j - 1) * T / m, j * T / m);
    x.segment(j * n_, n_) = z;
  }
  if (autonomous_) x[n_ * m] = period;
  winding_.setZero();
  const std::vector<int> angles = system_.angle_states();
  if (!angles.empty()) {
    // The gain of each angle over the guess's period, to the nearest whole turn: a guess within
    // half a turn of an orbit winds as the orbit does.
    const Eigen::VectorXd end = flow_.advance(z, p, (m - 1) * T / m, T);
    for (int a : angles) winding_[a] = kTwoPi * std::round((end[a] - starts(a, 0)) / kTwoPi);
  }
  return x;
}

std::vector<Flow*> ShootingProblem::team(Flow& flow) {
  const int size = std::min(options_.threads, options_.segments);
  std::vector<Flow*> flows{&flow};
  if (size < 2) return flows;
  auto& helpers = helpers_[&flow];
  while (static_cast<int>(helpers.size()) < size - 1)
    helpers.push_back(std::make_unique<Flow>(flow.system(), flow.options()));
  for (int w = 0; w < size - 1; ++w) flows.push_back(helpers[w].get());
  return flows;
}

FlowStatistics ShootingProblem::statistics() const {
  FlowStatistics s = flow_.statistics();
  for (const auto& f : plain_flows_)
    if (f) s += f->statistics();
  for (const auto& [flow, helpers] : helpers_)
    for (const auto& f : helpers) s += f->statistics();
  if (symmetric_) {
    s += symmetric_->flow.statistics();
    if (symmetric_->split_flow) s += symmetric_->split_flow->statistics();
    for (const auto& f : symmetric_->reduced_flows)
      if (f) s += f->statistics();
  }
  return s;
}

void ShootingProblem::reset_statistics() {
  flow_.reset_statistics();
  for (auto& f : plain_flows_)
    if (f) f->reset_statistics();
  for (auto& [flow, helpers] : helpers_)
    for (auto& f : helpers) f->reset_statistics();
  if (symmetric_) {
    symmetric_->flow.reset_statistics();
    if (symmetric_->split_flow) symmetric_->split_flow->reset_statistics();
    for (auto& f : symmetric_->reduced_flows)
      if (f) f->reset_statistics();
    symmetric_->served = 0;
    symmetric_->split_served = 0;
  }
}

FlowOptions ShootingProblem::plain_options(bool coarse) const {
  FlowOptions tight = options_.flow;
  // Not below 1e-13: CVODES reports tolerances near the unit roundoff as too much accuracy.
  tight.rtol = std::max(options_.flow.rtol / 100.0, std::min(options_.flow.rtol, 1e-13));
  tight.atol = options_.flow.atol / 10.0;
  if (coarse) {
    tight.rtol *= kCoarse;
    tight.atol *= kCoarse;
  }
  return tight;
}

Eigen::VectorXd ShootingProblem::residual(const Eigen::VectorXd& x, const ParameterValues& p,
                                          const PhaseSection& section, bool coarse) {
  Eigen::VectorXd r;
  if (symmetric_ && options_.segments == 1 && autonomous_)
    if (auto in_v = residual_in_subspace(x, p, coarse)) r = std::move(*in_v);
  if (!r.size()) {
    auto& flow = plain_flows_[coarse ? 1 : 0];
    if (!flow) flow = std::make_unique<Flow>(system_, plain_options(coarse));
    r = evaluate(x, p, false, -1, *flow).residual;
  }
  if (autonomous_) r[n_ * options_.segments] = section.offset(x.head(n_));
  return r;
}

std::optional<Eigen::VectorXd> ShootingProblem::residual_in_subspace(const Eigen::VectorXd& x,
                                                                     const ParameterValues& p,
                                                                     bool coarse) {
  SymmetricOrbit& s = *symmetric_;
  const auto& k = s.across.coordinates();
  const Eigen::VectorXd z0 = x.head(n_);
  const auto zV = symmetric_part(z0, p);
  if (!zV) return std::nullopt;
  const double T = period(x);
  if (!(T > 0.0)) throw IntegrationError("shooting: the period is not positive", 0.0);
  if (!s.reduced) s.reduced = std::make_unique<ReducedSystem>(system_, s.subspace);
  auto& flow = s.reduced_flows[coarse ? 1 : 0];
  if (!flow) flow = std::make_unique<Flow>(*s.reduced, plain_options(coarse));
  // The residual of z0's part in V (z0's part across V, at most 1e-13 of it, left out).
  Eigen::VectorXd r(unknowns());
  r.head(n_) = k.embed(flow->advance(k.restrict(*zV), p, 0.0, T)) - *zV - winding_;
  r[n_] = 0.0;  // the section's row: residual
  return r;
}

ShootingProblem::Evaluation ShootingProblem::evaluate(const Eigen::VectorXd& x,
                                                      const ParameterValues& p,
                                                      const PhaseSection& section, bool derivatives,
                                                      int parameter) {
  const bool symmetric =
      derivatives && symmetric_ && options_.segments == 1 && autonomous_ && record_samples_;
  std::optional<Evaluation> e;
  if (symmetric) {
    e = across_evaluation(x, p, parameter);
    if (!e && (e = split_evaluation(x, p, parameter))) remember(x, *e);
  }
  if (!e) {
    e = evaluate(x, p, derivatives, parameter, flow_);
    if (symmetric) remember(x, *e);
  }
  move_to_section(*e, x, section);
  return std::move(*e);
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
  // Each segment writes only its own slots (its transition, end rate, parameter column, residual
  // block and samples), so the segments may run on several threads in any order.
  if (derivatives) {
    e.transitions.resize(m);
    e.end_rates.resize(m);
  }
  const auto segment = [&](int j, Flow& f) {
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
      auto d = f.advance_with_sensitivities(
          zj, p, t0, t1, true, parameters, times,
          [&](double, const Eigen::VectorXd& z) { e.samples.states.col(k++) = z; });
      end = std::move(d.state);
      e.transitions[j] = std::move(d.transition);
      if (parameter >= 0) e.parameter_sensitivities.col(j) = d.parameter_sensitivities.col(0);
      e.end_rates[j] = system_.rhs(t1, end, p);
    } else {
      end = f.advance(zj, p, t0, t1);
    }
    e.residual.segment(j * n_, n_) = end - x.segment(((j + 1) % m) * n_, n_);
    if (j + 1 == m) e.residual.segment(j * n_, n_) -= winding_;
  };
  const std::vector<Flow*> flows = team(flow);
  if (flows.size() == 1) {
    for (int j = 0; j < m; ++j) segment(j, flow);
  } else {
    // Thread w integrates segments w, w + threads, ...: the same share each call. A failure is
    // rethrown after all have stopped, the first segment's that failed (as one thread would).
    std::vector<std::exception_ptr> failures(m);
    const auto share = [&](int w) {
      for (int j = w; j < m; j += static_cast<int>(flows.size())) {
        try {
          segment(j, *flows[w]);
        } catch (...) {
          failures[j] = std::current_exception();
          return;
        }
      }
    };
    std::vector<std::thread> threads;
    for (int w = 1; w < static_cast<int>(flows.size()); ++w) threads.emplace_back(share, w);
    share(0);
    for (auto& t : threads) t.join();
    for (const auto& failure : failures)
      if (failure) std::rethrow_exception(failure);
  }
  if (autonomous_) e.residual[n_ * m] = 0.0;  // the section's row: the public evaluate
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
  if (autonomous_ && e.section.normal.size() == n_)
    for (int i = 0; i < n_; ++i) t.emplace_back(n_ * m, i, e.section.normal[i]);
  Eigen::SparseMatrix<double> jac(rows, cols);
  jac.setFromTriplets(t.begin(), t.end());  // duplicates (M - I with one segment) are summed
  return jac;
}

}  // namespace sympathy
