#include "sympathy/continuation/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "sympathy/continuation/broyden.hpp"
#include "sympathy/core/assignment.hpp"
#include "sympathy/core/linear_solve.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

std::string to_string(BifurcationType t) {
  switch (t) {
    case BifurcationType::Fold:
      return "LP";
    case BifurcationType::BranchPoint:
      return "BP";
    case BifurcationType::PeriodDoubling:
      return "PD";
    case BifurcationType::NeimarkSacker:
      return "NS";
  }
  return "?";
}

std::string describe(BifurcationType t) {
  switch (t) {
    case BifurcationType::Fold:
      return "fold";
    case BifurcationType::BranchPoint:
      return "branch point";
    case BifurcationType::PeriodDoubling:
      return "period doubling";
    case BifurcationType::NeimarkSacker:
      return "Neimark-Sacker";
  }
  return "?";
}

struct Continuation::Corrected {
  bool converged = false;
  std::string reason;
  Eigen::VectorXd y;                       // (unknowns, parameter)
  ShootingProblem::Evaluation evaluation;  // at y, with sensitivities
  double residual = 0.0;                   // |F|_inf at y
  int iterations = 0;
  int chord_steps = 0;  // on plain integrations, before the iterations
};

namespace {

double inf_norm(const Eigen::VectorXd& v) {
  return v.size() ? v.cwiseAbs().maxCoeff() : 0.0;
}

// The multipliers that can cross the unit circle: neither the trivial one nor those a family of
// orbits forces to 1 (the Floquet analysis keeps the two kinds apart, even where one of these
// crosses 1 among them).
std::vector<Multiplier> nontrivial(const FloquetAnalysis& f) {
  std::vector<Multiplier> v;
  for (const auto& m : f.multipliers)
    if (!m.trivial && !m.structural) v.push_back(m);
  return v;
}

// Pairs (a_i, b_j) with the least total squared distance (the longer list's extra ones unpaired).
std::vector<std::pair<Multiplier, Multiplier>> match(const std::vector<Multiplier>& a,
                                                     const std::vector<Multiplier>& b) {
  const int n = static_cast<int>(std::max(a.size(), b.size()));
  Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(n, n);  // a row or column past the end: unpaired
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) cost(i, j) = std::norm(a[i].value - b[j].value);
  const std::vector<int> column = least_cost_assignment(cost);
  std::vector<std::pair<Multiplier, Multiplier>> pairs;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (column[i] < static_cast<int>(b.size())) pairs.emplace_back(a[i], b[column[i]]);
  return pairs;
}

bool is_real(std::complex<double> mu) {
  return std::abs(mu.imag()) <= 1e-6 * std::abs(mu);
}

// Multipliers of a followed to b. Each is first predicted at b by extrapolating its motion
// from the point before a (moved by `ratio` times its last step), then matched to the nearest
// of b's; `ambiguity` is the largest distance from a prediction to its match, relative to the
// gap from that match to its nearest neighbour at b (above 1/2 the match is doubtful). Only
// multipliers near the unit circle, and gaps above 0.01 (not collisions), count.
struct Tracked {
  std::vector<std::pair<Multiplier, Multiplier>> pairs;
  double ambiguity = 0.0;
};

Tracked follow(const std::vector<Multiplier>& a, const std::vector<Multiplier>* before,
               double ratio, const std::vector<Multiplier>& b) {
  std::vector<Multiplier> predicted = a;
  if (before && before->size() == a.size() && ratio > 0.0)
    for (const auto& [x, y] : match(*before, a))
      for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].value == y.value) predicted[i].value = y.value + ratio * (y.value - x.value);
  struct Link {
    Multiplier origin, predicted, match;
  };
  std::vector<Link> links;
  for (const auto& [p, y] : match(predicted, b)) {
    Multiplier origin = p;  // back from the prediction to a's own multiplier
    for (std::size_t i = 0; i < predicted.size(); ++i)
      if (predicted[i].value == p.value) origin = a[i];
    links.push_back({origin, p, y});
  }
  Tracked t;
  for (const auto& l : links) {
    // The gap to the nearest other match whose swap with this one could change a modulus: not
    // this one's complex conjugate, nor the match of its origin's conjugate (where two real
    // multipliers collide into a pair, or a pair splits, the two have one modulus either way).
    double gap = std::numeric_limits<double>::infinity();
    for (const auto& o : links) {
      const bool same = o.match.value == l.match.value;
      const bool conjugates =
          o.match.value == std::conj(l.match.value) || o.origin.value == std::conj(l.origin.value);
      if (!same && !conjugates) gap = std::min(gap, std::abs(o.match.value - l.match.value));
    }
    const double from_circle =
        std::min(std::abs(l.origin.modulus() - 1.0), std::abs(l.match.modulus() - 1.0));
    if (gap > 0.01 && from_circle < 0.1)
      t.ambiguity = std::max(t.ambiguity, std::abs(l.predicted.value - l.match.value) / gap);
    t.pairs.emplace_back(l.origin, l.match);
  }
  return t;
}

}  // namespace

Continuation::Continuation(OdeSystem& system, int parameter, ContinuationOptions options)
    : system_(system), parameter_(parameter), options_(std::move(options)) {
  if (!system.autonomous())
    throw std::invalid_argument("continuation: for autonomous systems (periodic orbits)");
  if (!(options_.upper > options_.lower))
    throw std::invalid_argument("continuation: the upper bound must exceed the lower bound");
  if (options_.max_parameter_step <= 0.0)
    options_.max_parameter_step = (options_.upper - options_.lower) / 25.0;
  problem_ = std::make_unique<ShootingProblem>(system_, options_.orbit.shooting);
}

// Normal to the flow at z in the scaled norm: in units of the orbits' sizes an oscillation is
// nearly circular, and a section normal to the flow there contains the directions in which its
// amplitude changes, so that the points do not slide along the orbits as the branch goes on (in
// raw units the normal is dominated by the large rates of the velocities, and the section is
// nearly a level of one velocity, which a shrinking swing leaves).
Eigen::VectorXd Continuation::section_normal(const Eigen::VectorXd& z) const {
  const Eigen::VectorXd w = weights_.head(problem_->dimension());
  return w.array().square() * system_.rhs(0.0, z).array();
}

double Continuation::scaled_dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
  return (weights_.array().square() * u.array() * v.array()).sum();
}

// The direction of a shift in time along the orbits at y: f at each segment's state, nothing in
// the period or the parameter. Sections and phase drift move tangents along it without any
// change of orbit, so comparisons of tangents leave it out.
Eigen::VectorXd Continuation::time_shift(const Eigen::VectorXd& y) const {
  const int n = problem_->dimension(), m = problem_->segments();
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(y.size());
  for (int j = 0; j < m; ++j) phi.segment(j * n, n) = system_.rhs(0.0, y.segment(j * n, n));
  return phi;
}

double Continuation::orbit_cosine(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                                  const Eigen::VectorXd& at) const {
  const Eigen::VectorXd phi = time_shift(at);
  const double pp = scaled_dot(phi, phi);
  auto strip = [&](const Eigen::VectorXd& x) {
    return pp > 0.0 ? Eigen::VectorXd(x - scaled_dot(x, phi) / pp * phi) : x;
  };
  const Eigen::VectorXd a = strip(u), b = strip(v);
  const double norms = std::sqrt(scaled_dot(a, a) * scaled_dot(b, b));
  return norms > 0.0 ? scaled_dot(a, b) / norms : 0.0;
}

// The largest |z_i| on an orbit (one period, sampled) widens each component's scale: scales only
// grow, so that a component whose amplitude grows along the branch (a platform starting to
// swing) does not take all the arclength.
void Continuation::widen_scales(const Eigen::VectorXd& z0, double period) {
  Flow flow(system_, options_.orbit.transient_flow);
  Eigen::VectorXd size = z0.cwiseAbs();
  std::vector<double> times;
  for (int k = 1; k <= 100; ++k) times.push_back(period * k / 100.0);
  flow.sample(z0, 0.0, times,
              [&](double, const Eigen::VectorXd& z) { size = size.cwiseMax(z.cwiseAbs()); });
  sizes_ = sizes_.size() ? Eigen::VectorXd(sizes_.cwiseMax(size)) : size;
  const int n = problem_->dimension(), m = problem_->segments();
  const double floor = std::max(1e-3 * sizes_.maxCoeff(), 1e-12);
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < n; ++i)
      weights_[j * n + i] = 1.0 / (std::max(sizes_[i], floor) * std::sqrt(static_cast<double>(m)));
}

void Continuation::set_weights(const PeriodicOrbit& start) {
  const int n = problem_->dimension(), m = problem_->segments();
  const int unknowns = problem_->unknowns();
  weights_.resize(unknowns + 1);
  sizes_.resize(0);
  widen_scales(start.state0, start.period);
  weights_[n * m] = 1.0 / start.period;
  weights_[unknowns] = 1.0 / (options_.upper - options_.lower);
}

// The shooting Jacobian (with its parameter column) bordered by one more row.
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

// Newton on the bordered system (shooting equations and arclength), each iteration with the
// flow's sensitivities: the converged point's monodromy is the stability's and the next
// tangent's. Before it, quasi-Newton steps on plain residuals as accurate as those runs
// (ShootingProblem::residual) do most of the work.
Continuation::Corrected Continuation::correct(const Eigen::VectorXd& from,
                                              const Eigen::VectorXd& tangent, double step,
                                              const Eigen::VectorXd& start_guess,
                                              const Eigen::SparseMatrix<double>* chord) {
  const int N = problem_->unknowns();
  Corrected c;
  Eigen::VectorXd y = start_guess;
  const Eigen::VectorXd row = weights_.array().square() * tangent.array();
  LinearSolveOptions linear;
  linear.prefer_sparse = problem_->segments() > 1;
  linear.rank_tolerance = options_.orbit.newton.rank_tolerance;
  auto rhs_at = [&](const Eigen::VectorXd& residual) {
    Eigen::VectorXd rhs(N + 1);
    rhs.head(N) = -residual;
    rhs[N] = -(row.dot(y - from) - step);
    return rhs;
  };
  const double tolerance =
      attainable_tolerance(options_.corrector_tolerance, options_.orbit.newton.rtol_factor,
                           options_.orbit.shooting.flow);
  int iterations = 0;
  // Quasi-Newton steps first, on plain integrations (about a tenth of the cost of one with
  // sensitivities): Broyden's updates of `chord` (the Jacobian extrapolated from the last points),
  // in the scaled norm, while they contract. They aim well below the tolerance, so that one
  // integration with sensitivities at their end usually both confirms the point and gives its
  // monodromy.
  if (chord && options_.max_chord_steps > 0) {
    const auto matrix = bordered(*chord, row);
    std::vector<Eigen::VectorXd> steps;
    double last = std::numeric_limits<double>::infinity();
    Eigen::VectorXd before = y;
    for (int k = 0; k < options_.max_chord_steps; ++k) {
      system_.set_parameter(parameter_, y[N]);
      Eigen::VectorXd residual;
      try {
        residual = problem_->residual(y.head(N));
      } catch (const IntegrationError&) {
        y = before;
        break;
      }
      const double norm = inf_norm(residual);
      if (norm <= 0.25 * tolerance) break;
      // Not contracting: Newton takes over, from the better of the last two.
      if (norm > 0.5 * last) {
        if (norm > last) y = before;
        break;
      }
      const auto z = broyden_step(solve_linear(matrix, rhs_at(residual), linear).x, steps,
                                  [&](const auto& u, const auto& v) { return scaled_dot(u, v); });
      if (!z || !z->allFinite()) break;
      steps.push_back(*z);
      before = y;
      y += *z;
      ++c.chord_steps;
      last = norm;
    }
  }
  double previous = std::numeric_limits<double>::infinity();
  for (int it = 0;; ++it, ++iterations) {
    system_.set_parameter(parameter_, y[N]);
    ShootingProblem::Evaluation e;
    try {
      e = problem_->evaluate(y.head(N), true, parameter_);
    } catch (const IntegrationError& error) {
      c.reason = error.what();
      return c;
    }
    const double norm = inf_norm(e.residual);
    // Converged; or stalled within ten tolerances: the integration's noise floor, not a failure.
    const bool stalled = it >= 1 && norm > 0.3 * previous && norm <= 10 * tolerance;
    if (norm <= tolerance || stalled) {
      c.converged = true;
      c.y = std::move(y);
      c.evaluation = std::move(e);
      c.residual = norm;
      c.iterations = iterations;
      return c;
    }
    if (it >= options_.max_corrector_iterations || (it >= 2 && norm > previous)) {
      std::ostringstream msg;
      msg << "corrector " << (norm > previous ? "diverged" : "did not converge") << " (residual "
          << norm << " after " << iterations << " iterations)";
      c.reason = msg.str();
      return c;
    }
    previous = norm;
    const auto dy =
        solve_linear(bordered(problem_->jacobian(e, true), row), rhs_at(e.residual), linear);
    if (!dy.x.allFinite()) {
      c.reason = "corrector step not finite";
      return c;
    }
    y += dy.x;
  }
}

// The predictor: along the tangent at a, or, when the point before a shares a's phase section
// (the unknowns then lie on one smooth curve), along the cubic through both points with their
// tangents. Its error is O(ds^3) instead of O(ds^2): one corrector iteration fewer per point.
Eigen::VectorXd Continuation::predict(const ContinuationPoint* before, const ContinuationPoint& a,
                                      double ds) const {
  const int N = problem_->unknowns();
  Eigen::VectorXd ya(N + 1);
  ya << a.unknowns, a.parameter;
  Eigen::VectorXd guess = ya + ds * a.tangent;
  if (!options_.curved_predictor || !before || before->section.size() != a.section.size() ||
      before->section != a.section)
    return guess;
  Eigen::VectorXd y0(N + 1);
  y0 << before->unknowns, before->parameter;
  const double h = std::sqrt(scaled_dot(ya - y0, ya - y0));  // chord length from before to a
  if (!(h > 0.0) || ds > 3.0 * h) return guess;
  // Y(s) = ya + s t1 + c2 s^2 + c3 s^3 with Y(-h) = y0, Y'(-h) = t0 (tangents in the current
  // scaled norm; the previous one renormalized there).
  const Eigen::VectorXd& t1 = a.tangent;
  const Eigen::VectorXd t0 =
      before->tangent / std::sqrt(scaled_dot(before->tangent, before->tangent));
  if (scaled_dot(t0, t1) < options_.min_tangent_cosine) return guess;
  const Eigen::VectorXd D = y0 - ya + h * t1, E = t0 - t1;
  const Eigen::VectorXd c2 = (3.0 * D / h + E) / h;
  const Eigen::VectorXd c3 = (c2 * h * h - D) / (h * h * h);
  return guess + ds * ds * (c2 + ds * c3);
}

// The unit tangent from a shooting Jacobian (with its parameter column), in the problem's current
// phase section (the one the next step's corrector uses), oriented along `previous`.
Eigen::VectorXd Continuation::tangent_of(const Eigen::SparseMatrix<double>& jac,
                                         const Eigen::VectorXd& y,
                                         const Eigen::VectorXd& previous) const {
  const int N = problem_->unknowns();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(N + 1);
  rhs[N] = 1.0;
  LinearSolveOptions linear;
  linear.prefer_sparse = problem_->segments() > 1;
  linear.rank_tolerance = options_.orbit.newton.rank_tolerance;
  const Eigen::VectorXd row = weights_.array().square() * previous.array();
  Eigen::VectorXd tau = solve_linear(bordered(jac, row), rhs, linear).x;
  tau /= std::sqrt(scaled_dot(tau, tau));
  if (orbit_cosine(tau, previous, y) < 0.0) tau = -tau;
  return tau;
}

ContinuationPoint Continuation::make_point(const Corrected& c, const Eigen::VectorXd& tangent,
                                           int index, double step) {
  const int N = problem_->unknowns(), n = problem_->dimension(), m = problem_->segments();
  ContinuationPoint p;
  p.index = index;
  p.parameter = c.y[N];
  p.unknowns = c.y.head(N);
  p.tangent = tangent;
  p.section = problem_->phase_reference();
  p.section_normal = problem_->phase_normal();
  p.step = step;
  p.iterations = c.iterations;
  PeriodicOrbit& o = p.orbit;
  o.state0 = c.y.head(n);
  o.period = c.y[n * m];
  o.segments = m;
  o.residual = c.residual;
  o.family_dimension = family_dimension_;
  system_.set_parameter(parameter_, p.parameter);
  o.floquet = shooting_floquet(*problem_, c.evaluation, o.state0, family_dimension_,
                               options_.orbit.floquet);
  o.newton.converged = true;
  o.newton.iterations = c.iterations;
  o.newton.reason = "corrector converged";
  return p;
}

Branch Continuation::run(const PeriodicOrbit& start, int direction,
                         const ContinuationCallbacks& callbacks,
                         const Eigen::VectorXd& initial_tangent) {
  const Stopwatch started;
  Branch branch;
  branch.parameter_name = system_.parameter_names()[parameter_];
  problem_->reset_statistics();
  auto finish = [&](const std::string& reason) {
    branch.stop_reason = reason;
    branch.flow = problem_->statistics();
    branch.seconds = started.seconds();
    return branch;
  };
  const int N = problem_->unknowns();
  try {
    set_weights(start);
  } catch (const IntegrationError& e) {
    return finish(std::string("the starting orbit cannot be integrated: ") + e.what());
  }

  // The starting point, corrected at its parameter value.
  const double p0 = system_.parameter(parameter_);
  problem_->set_phase_section(start.state0, section_normal(start.state0));
  Eigen::VectorXd y0(N + 1);
  try {
    y0.head(N) = problem_->unknowns_from(start.state0, start.period);
  } catch (const IntegrationError& e) {
    return finish(std::string("the starting orbit cannot be integrated: ") + e.what());
  }
  y0[N] = p0;
  Eigen::VectorXd along_parameter = Eigen::VectorXd::Zero(N + 1);
  along_parameter[N] = 1.0 / weights_[N];  // unit in the scaled norm
  const Corrected c0 = correct(y0, along_parameter, 0.0, y0, nullptr);
  if (!c0.converged) return finish("the starting orbit does not converge: " + c0.reason);
  // A continuum of orbits persists along the branch: its dimension is decided once, here, not
  // at each point (near a branch point the Jacobian is nearly singular too, for other reasons).
  family_dimension_ =
      rank_deficiency(problem_->jacobian(c0.evaluation), options_.orbit.newton.rank_tolerance);
  Eigen::VectorXd tau;
  if (initial_tangent.size() == N + 1) {
    tau = initial_tangent / std::sqrt(scaled_dot(initial_tangent, initial_tangent));
  } else {
    tau = tangent_of(problem_->jacobian(c0.evaluation, true), c0.y, direction * along_parameter);
  }
  chord_jacobian_ = problem_->jacobian(c0.evaluation, true);
  branch.points.push_back(make_point(c0, tau, 0, 0.0));
  if (callbacks.on_point) callbacks.on_point(branch.points.back());

  double ds = options_.initial_step;
  int location_retries = 0;  // shorter tries of the current step for an unlocated event
  for (;;) {
    if (callbacks.stop_requested && callbacks.stop_requested()) return finish("interrupted");
    if (static_cast<int>(branch.points.size()) >= options_.max_points)
      return finish("point limit (" + std::to_string(options_.max_points) + ") reached");
    const ContinuationPoint& a = branch.points.back();
    const double dp_per_ds = std::abs(a.tangent[N]);
    if (ds * dp_per_ds > options_.max_parameter_step)
      ds = std::max(options_.max_parameter_step / dp_per_ds, options_.min_step);
    Eigen::VectorXd ya(N + 1);
    ya << a.unknowns, a.parameter;
    problem_->set_phase_section(a.section, a.section_normal);
    const ContinuationPoint* previous =
        branch.points.size() >= 2 ? &branch.points[branch.points.size() - 2] : nullptr;
    // The quasi-Newton steps start from the Jacobian extrapolated along the branch from the last
    // two points (when they share a's section): its error is then O(ds^2), not O(ds).
    Eigen::SparseMatrix<double> chord = chord_jacobian_;
    if (previous && previous->section == a.section && a.step > 0.0 &&
        jacobian_before_.rows() == chord.rows() && jacobian_before_.cols() == chord.cols())
      chord = chord_jacobian_ + (ds / a.step) * (chord_jacobian_ - jacobian_before_);
    const Corrected c = correct(ya, a.tangent, ds, predict(previous, a, ds), &chord);
    if (!c.converged) {
      ++branch.rejected.corrector;
      ds *= 0.5;
      if (ds < options_.min_step) return finish("step size below the minimum: " + c.reason);
      continue;
    }
    // The section stays while the flow crosses it well (the angle in the scaled norm): kept, the
    // points lie on one smooth curve, which the predictor and the extrapolated Jacobian follow.
    const int n = problem_->dimension();
    const Eigen::VectorXd zb = c.y.head(n);
    const Eigen::VectorXd w = weights_.head(n);
    const Eigen::VectorXd flow_b = w.asDiagonal() * system_.rhs(0.0, zb);
    const Eigen::VectorXd flow_ref = w.cwiseInverse().asDiagonal() * problem_->phase_normal();
    const double crossing = flow_ref.normalized().dot(flow_b.normalized());
    if (crossing < 0.9) problem_->set_phase_section(zb, section_normal(zb));
    auto jacobian_b = problem_->jacobian(c.evaluation, true);
    const Eigen::VectorXd tau_b = tangent_of(jacobian_b, c.y, a.tangent);
    if (orbit_cosine(tau_b, a.tangent, c.y) < options_.min_tangent_cosine &&
        ds > 4 * options_.min_step) {
      ++branch.rejected.turn;
      ds *= 0.5;
      continue;
    }
    ContinuationPoint b = make_point(c, tau_b, a.index + 1, ds);
    // Multipliers whose modulus moves far in one step near the unit circle may hide a window of
    // instability; any that moves very far makes the matching of multipliers doubtful.
    // A multiplier near the circle whose modulus moves far in one step may hide a window of
    // instability; one whose match at b is doubtful (followed with its predicted motion)
    // makes crossings unreliable.
    const auto tracked = track(previous, a, b);
    bool too_far = tracked.ambiguity > 0.5;
    double watched_change = 0.0;  // largest change of |mu| near the circle in this step
    for (const auto& [mx, my] : tracked.pairs) {
      const auto x = mx.value, y = my.value;
      const bool near =
          std::min(std::abs(std::abs(x) - 1.0), std::abs(std::abs(y) - 1.0)) < options_.watch_band;
      if (near) watched_change = std::max(watched_change, std::abs(std::abs(x) - std::abs(y)));
    }
    too_far |= watched_change > options_.max_modulus_change;
    // A step whose multipliers could not be matched with confidence, or moved too far, is
    // rejected after its whole cost: the retry, and the step after an accepted one, aim below
    // both limits at the rates just seen (the modulus change grows like ds, a matching error like
    // ds^2).
    double aim = std::numeric_limits<double>::infinity();
    if (watched_change > 0.0) aim = 0.75 * options_.max_modulus_change / watched_change * ds;
    if (tracked.ambiguity > 0.0) aim = std::min(aim, std::sqrt(0.3 / tracked.ambiguity) * ds);
    if (too_far && ds > 4 * options_.min_step) {
      ++branch.rejected.multipliers;
      ds = std::max(std::min(0.5 * ds, aim), 4 * options_.min_step);
      continue;
    }
    std::vector<Bifurcation> events;
    if (options_.detect_bifurcations) {
      events = detect(tracked, a, b);
      // An event that could not be located in this step: try a shorter one (the multipliers
      // are then easier to follow), unless the step is short already.
      const bool unlocated =
          std::any_of(events.begin(), events.end(), [](const auto& e) { return !e.located; });
      if (unlocated && location_retries < 3 && ds > 4 * options_.min_step) {
        ++branch.rejected.location;
        ++location_retries;
        ds *= 0.5;
        continue;
      }
    }
    location_retries = 0;
    branch.points.push_back(std::move(b));
    jacobian_before_ = std::move(chord_jacobian_);
    chord_jacobian_ = std::move(jacobian_b);
    const ContinuationPoint& added = branch.points.back();
    if (callbacks.on_point) callbacks.on_point(added);
    for (auto& e : events) {
      branch.events.push_back(std::move(e));
      if (callbacks.on_event) callbacks.on_event(branch.events.back());
    }
    if (added.parameter < options_.lower || added.parameter > options_.upper)
      return finish("reached the parameter bound");
    // Scales follow the amplitudes met so far; the tangent stays a unit vector in them.
    try {
      widen_scales(added.orbit.state0, added.orbit.period);
    } catch (const IntegrationError&) {
      // keep the scales as they are
    }
    auto& last = branch.points.back();
    last.tangent /= std::sqrt(scaled_dot(last.tangent, last.tangent));
    if (c.iterations <= 2)
      ds = std::min(1.5 * ds, options_.max_step);
    else if (c.iterations >= 5)
      ds *= 0.6;
    ds = std::max(std::min(ds, aim), std::min(ds, 4 * options_.min_step));
  }
}

Continuation::Followed Continuation::track(const ContinuationPoint* before,
                                           const ContinuationPoint& a,
                                           const ContinuationPoint& b) const {
  const auto na = nontrivial(a.orbit.floquet), nb = nontrivial(b.orbit.floquet);
  const double ratio = a.step > 0.0 ? b.step / a.step : 0.0;
  if (before) {
    const auto nbefore = nontrivial(before->orbit.floquet);
    const auto t = follow(na, &nbefore, ratio, nb);
    return {t.pairs, t.ambiguity};
  }
  const auto t = follow(na, nullptr, 0.0, nb);
  return {t.pairs, t.ambiguity};
}

std::vector<Bifurcation> Continuation::detect(const Followed& tracked, const ContinuationPoint& a,
                                              const ContinuationPoint& b) {
  const int N = problem_->unknowns();
  const bool fold = a.tangent[N] * b.tangent[N] < 0.0;
  struct Crossing {
    std::complex<double> a, b;
  };
  std::vector<Crossing> plus, minus, complex;
  {
    // Every multiplier that can cross is followed (not the trivial one, nor a family's).
    for (const auto& [mx, my] : tracked.pairs) {
      const auto x = mx.value, y = my.value;
      if ((std::abs(x) - 1.0) * (std::abs(y) - 1.0) >= 0.0) continue;
      if (is_real(x) && is_real(y)) {
        (x.real() > 0 ? plus : minus).push_back({x, y});
      } else if (x.imag() > 0.0 || y.imag() > 0.0) {
        complex.push_back({x, y});  // one of each conjugate pair
      }
    }
  }
  // Crossings with equal multipliers happen together (symmetry): one event, its multiplicity.
  auto clusters = [](const std::vector<Crossing>& c) {
    std::vector<std::vector<Crossing>> groups;
    for (const auto& x : c) {
      bool placed = false;
      for (auto& g : groups)
        if (std::abs(g.front().a - x.a) <= 1e-6 * std::max(1.0, std::abs(x.a))) {
          g.push_back(x);
          placed = true;
          break;
        }
      if (!placed) groups.push_back({x});
    }
    return groups;
  };
  std::vector<Bifurcation> found;
  auto report = [&](Bifurcation e) {
    e.after_point = a.index;
    const double worst = std::max(
        {a.orbit.floquet.trivial_error, b.orbit.floquet.trivial_error, e.floquet.trivial_error});
    if (worst > options_.trust_limit) {
      e.trusted = false;
      std::ostringstream msg;
      msg << "not trusted: trivial-multiplier error " << worst << " above " << options_.trust_limit;
      e.note += (e.note.empty() ? "" : "; ") + msg.str();
    }
    found.push_back(std::move(e));
  };
  auto plus_groups = clusters(plus);
  if (fold) {
    Bifurcation e = locate(a, b, BifurcationType::Fold, 1, {}, {});
    if (plus_groups.empty())
      e.note = "no multiplier crossing +1 seen between the bracketing points";
    report(e);
    if (!plus_groups.empty()) plus_groups.erase(plus_groups.begin());
  }
  for (const auto& g : plus_groups) {
    Bifurcation e = locate(a, b, BifurcationType::BranchPoint, static_cast<int>(g.size()),
                           g.front().a, g.front().b);
    if (g.size() > 1) e.note = std::to_string(g.size()) + " multipliers cross +1 together";
    report(e);
  }
  for (const auto& g : clusters(minus)) {
    Bifurcation e = locate(a, b, BifurcationType::PeriodDoubling, static_cast<int>(g.size()),
                           g.front().a, g.front().b);
    if (g.size() > 1) e.note = std::to_string(g.size()) + " multipliers cross -1 together";
    report(e);
  }
  for (const auto& g : clusters(complex)) {
    Bifurcation e = locate(a, b, BifurcationType::NeimarkSacker, static_cast<int>(g.size()),
                           g.front().a, g.front().b);
    if (g.size() > 1) e.note = std::to_string(g.size()) + " complex pairs cross together";
    report(e);
  }
  std::stable_sort(found.begin(), found.end(),
                   [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
  return found;
}

Bifurcation Continuation::locate(const ContinuationPoint& a, const ContinuationPoint& b,
                                 BifurcationType type, int multiplicity, std::complex<double> mu_a,
                                 std::complex<double> mu_b) {
  const int N = problem_->unknowns();
  Eigen::VectorXd ya(N + 1);
  ya << a.unknowns, a.parameter;
  const double sb = b.step;
  // The multiplier followed across, by continuity: the one nearest the value interpolated
  // between the multipliers followed at the current ends of the bracket (for a fold, the
  // nontrivial one nearest to 1).
  double s_lo = 0.0, s_hi = sb;
  std::complex<double> mu_lo = mu_a, mu_hi = mu_b;
  auto tracked = [&](const ContinuationPoint& p, double s) {
    const std::complex<double> expected =
        type == BifurcationType::Fold ? 1.0 : mu_lo + (s - s_lo) / (s_hi - s_lo) * (mu_hi - mu_lo);
    std::complex<double> found = 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& m : nontrivial(p.orbit.floquet))
      if (std::abs(m.value - expected) < best) {
        best = std::abs(m.value - expected);
        found = m.value;
      }
    return found;
  };
  // The test function: the tangent's parameter component for a fold; |mu| - 1 of the
  // multiplier followed otherwise.
  auto test = [&](const ContinuationPoint& p, std::complex<double> mu) {
    return type == BifurcationType::Fold ? p.tangent[N] : std::abs(mu) - 1.0;
  };
  Bifurcation e;
  e.type = type;
  e.multiplicity = multiplicity;
  double f_lo = test(a, mu_a), f_hi = test(b, mu_b);
  ContinuationPoint lo = a, hi = b, best = std::abs(f_lo) < std::abs(f_hi) ? a : b;
  double f_best = std::min(std::abs(f_lo), std::abs(f_hi));
  std::complex<double> mu_best = std::abs(f_lo) < std::abs(f_hi) ? mu_a : mu_b;
  double s_best = std::abs(f_lo) < std::abs(f_hi) ? 0.0 : sb;
  int side = 0;  // Illinois: which end was kept last time
  problem_->set_phase_section(a.section, a.section_normal);
  for (int iteration = 0; iteration < 30; ++iteration) {
    const double scale = std::max(std::abs(best.parameter), 1.0);
    const bool narrow =
        std::abs(hi.parameter - lo.parameter) <= options_.location_tolerance * scale;
    const bool tight = (s_hi - s_lo) <= 1e-7 * sb;  // folds: the parameter is flat there
    if ((narrow && (type != BifurcationType::Fold || tight)) || f_best == 0.0) {
      e.located = true;
      break;
    }
    double s = s_hi - f_hi * (s_hi - s_lo) / (f_hi - f_lo);
    if (!(s > s_lo && s < s_hi)) s = 0.5 * (s_lo + s_hi);
    // At least half the tolerance (in arclength) inside each end: when the root lies next to
    // one end, a probe just past it closes the bracket at once, where the secant would creep up
    // on it from one side.
    const double dp_ds = std::abs(hi.parameter - lo.parameter) / (s_hi - s_lo);
    const double half_tolerance = type == BifurcationType::Fold || !(dp_ds > 0.0)
                                      ? 0.5e-7 * sb
                                      : 0.5 * options_.location_tolerance * scale / dp_ds;
    const double inset = std::min(half_tolerance, 0.25 * (s_hi - s_lo));
    s = std::clamp(s, s_lo + inset, s_hi - inset);
    const Corrected c = correct(ya, a.tangent, s, ya + s * a.tangent, &chord_jacobian_);
    if (!c.converged) {
      e.note = "location stopped: " + c.reason;
      break;
    }
    const Eigen::VectorXd tau = tangent_of(problem_->jacobian(c.evaluation, true), c.y, a.tangent);
    ContinuationPoint p = make_point(c, tau, a.index, s);
    const std::complex<double> mu = tracked(p, s);
    const double f = test(p, mu);
    if (std::abs(f) < f_best) {
      f_best = std::abs(f);
      best = p;
      mu_best = mu;
      s_best = s;
    }
    if ((f > 0) == (f_hi > 0)) {
      s_hi = s;
      f_hi = f;
      mu_hi = mu;
      hi = std::move(p);
      if (side == +1) f_lo *= 0.5;
      side = +1;
    } else {
      s_lo = s;
      f_lo = f;
      mu_lo = mu;
      lo = std::move(p);
      if (side == -1) f_hi *= 0.5;
      side = -1;
    }
  }
  e.parameter = best.parameter;
  e.arclength = s_best;
  e.uncertainty = std::abs(hi.parameter - lo.parameter);
  e.period = best.orbit.period;
  e.floquet = best.orbit.floquet;
  e.crossing = type == BifurcationType::Fold ? tracked(best, 0.0) : mu_best;
  if (e.crossing.imag() < 0.0) e.crossing = std::conj(e.crossing);
  e.state0 = best.orbit.state0;
  e.unknowns = best.unknowns;
  e.tangent = best.tangent;
  if (!e.located && e.note.empty()) e.note = "location did not reach the tolerance";
  system_.set_parameter(parameter_, b.parameter);  // where the run goes on from
  return e;
}

}  // namespace sympathy
