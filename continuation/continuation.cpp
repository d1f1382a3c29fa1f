#include "sympathy/continuation/continuation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

#include "stiffness_choice.hpp"
#include "sympathy/continuation/detection.hpp"
#include "sympathy/continuation/driver.hpp"
#include "sympathy/continuation/homoclinic_approach.hpp"
#include "sympathy/continuation/hopf.hpp"
#include "sympathy/continuation/location.hpp"
#include "sympathy/continuation/multiplier_tracking.hpp"
#include "sympathy/continuation/predictor.hpp"
#include "sympathy/continuation/step_control.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/hybrid_system.hpp"
#include "sympathy/core/linear_solve.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace detail {
// A point of an orbit branch as the driver follows it: with its shooting Jacobian (in the section
// of the step that found it), which location interpolates and the next step starts from.
struct OrbitNode : ContinuationPoint {
  Eigen::SparseMatrix<double> jacobian;
  // The largest growth over one segment of half as many (Growth::halved): whether the point
  // would be resolved on fewer segments. Infinite where not measured.
  double halved_growth = std::numeric_limits<double>::infinity();
};
}  // namespace detail
using detail::OrbitNode;

class Continuation::Run {
 public:
  using Point = OrbitNode;
  using Event = Bifurcation;
  explicit Run(Continuation& c);
  double limit_step(const OrbitNode& a, double ds) const;
  driver::Attempt<OrbitNode> step(const OrbitNode* before, const OrbitNode& a, double ds);
  double turn_cosine(const OrbitNode& a, const OrbitNode& b) const;
  driver::Screen screen(const OrbitNode* before, const OrbitNode& a, const OrbitNode& b, double ds);
  bool outside(const OrbitNode& b) const;
  std::string edge_message(const OrbitNode& b) const;
  std::string past_note() const;
  std::optional<OrbitNode> onto_edge(const OrbitNode& a, const OrbitNode& b);
  driver::Found<Bifurcation> detect(const OrbitNode* before, const OrbitNode& a,
                                    const OrbitNode& b);
  std::optional<driver::Ending> ends(const OrbitNode& a, const OrbitNode& b,
                                     std::vector<Bifurcation>& events);
  void accept(OrbitNode& b);
  bool refine(OrbitNode& a, const std::string& why);
  bool resample(OrbitNode& a, int segments);
  // The most shooting segments a refinement takes a branch to; past its homoclinic approach,
  // toward a longer period asked for, kMostSegmentsPast (AUTO's ab at p2 = 17 to T = 1000: 512
  // segments from T 815 on, about 2 s each).
  static constexpr int kMostSegments = 8, kMostSegmentsPast = 1024;
  // A branch on more segments than asked goes back to half as many after this many accepted
  // points in a row whose growth on half (OrbitNode::halved_growth) stays below kHalvedGrowth:
  // a hundredth of the lowest growth at which one segment was seen to fail (1.3e4, AUTO's ab
  // at p2 = 15), so that a coarsened branch is far from needing the segments again.
  static constexpr double kHalvedGrowth = 100.0;
  static constexpr int kResolvedPoints = 3;
  double parameter(const OrbitNode& p) const { return p.parameter; }

  std::optional<HopfPoint> hopf_end;  // where the family ended at a Hopf point

 private:
  Eigen::VectorXd y_of(const OrbitNode& p) const;  // (unknowns, parameter)
  // Whether an accepted point keeps its period's samples: where a user value reads the orbits'
  // extremes, the next step's detect reads them (else one plain period is integrated again).
  bool keeps_samples() const {
    return std::any_of(c_.options_.user_values.begin(), c_.options_.user_values.end(),
                       [](const UserValue& v) {
                         return v.quantity == UserValue::Quantity::Maximum ||
                                v.quantity == UserValue::Quantity::Minimum;
                       });
  }
  // Continuation::hopf_end of a turn, asked once per located turn: detection asks it to decide
  // whether to retry the step, ends to end the family there (a secant search on the equilibria
  // and their Lyapunov coefficient each time).
  const std::optional<HopfPoint>& hopf_end_of(const Bifurcation& turn);
  std::optional<std::pair<Eigen::Vector2d, std::optional<HopfPoint>>> hopf_asked_;
  Continuation& c_;
  int N_;
  std::vector<Eigen::VectorXd> path_;  // the accepted points' (unknowns, parameter), in order
  std::vector<PeriodRecord> periods_;  // the accepted points', for homoclinic_approach
  // The screen's pairing of the multipliers from a to the b it saw, which detection reuses.
  TrackedMultipliers tracked_;
  Eigen::VectorXd tracked_unknowns_;
  double tracked_parameter_ = 0.0;
  // The first turn without a multiplier at +1: the points before it (their count in path_) and
  // its parameter.
  std::optional<std::pair<std::size_t, double>> turn_;
  int resolved_points_ = 0;  // in a row, resolved on half the segments (kHalvedGrowth)
  // The first value to stop at that detect located in the step: its arclength from a and note.
  std::optional<std::pair<double, std::string>> stop_at_;
  // Where the branch went on past its homoclinic approach toward a longer period asked for
  // (AUTO's UZSTOP on PERIOD): beyond, steps are neither screened nor searched for bifurcations,
  // and the branch's stop message says from where. Their multipliers are noise there (on AUTO's
  // ab at p2 = 17 a PD, an NS and a BP every few points, trivial errors up to 1e220), and the
  // parameter stays within its rounding while the period grows (ab: p1 = 0.12010169875 from
  // T 90 to 1000), so that the sign of the tangent's parameter component, which finds folds,
  // is noise too (an LP at T 325, 1e-14 wide, whose turn then ended the branch).
  std::optional<PeriodRecord> past_;
  // The shortest segment duration (period / segments) at which the corrector failed and the
  // branch was refined. Past the homoclinic approach the period grows without bound and the
  // parameter stays put, so the segments are doubled before their duration comes back to 3/4 of
  // it (AUTO's ab at p2 = 17 failed at 6.5, 5.6, 5.5, 4.3 and 5.2 s a segment from T 26 to 330;
  // each failure cost 30-50 points: the step shortened to the minimum, then grown again).
  double failed_duration_ = std::numeric_limits<double>::infinity();
  // A hybrid system's: the last accepted point's crossings per period (grazing.hpp), and those
  // of the step's end that ends() computed, which accept() keeps.
  const bool carries_crossings_;  // a hybrid system with switching surfaces
  std::vector<int> crossings_, crossings_b_;
};

OptionCheck ContinuationOptions::validate() const {
  if (!positive(min_step)) return OptionProblem{"min_step", "a positive number"};
  if (!(positive(initial_step) && initial_step >= min_step))
    return OptionProblem{"initial_step", "a positive number, at least the minimum step"};
  if (!(std::isfinite(max_step) && max_step >= initial_step))
    return OptionProblem{"max_step", "a number at least the initial step (--step)"};
  if (!non_negative(max_parameter_step))
    return OptionProblem{"max_parameter_step",
                         "0 (the range over parameter_steps) or a positive number"};
  if (!(positive(parameter_steps) && parameter_steps >= 1.0))
    return OptionProblem{"parameter_steps", "a number of at least 1"};
  if (max_points < 2) return OptionProblem{"max_points", "an integer of at least 2"};
  if (max_corrector_iterations < 1)
    return OptionProblem{"max_corrector_iterations", "a positive integer"};
  if (max_chord_steps < 0) return OptionProblem{"max_chord_steps", "a non-negative integer"};
  if (!positive(corrector_tolerance))
    return OptionProblem{"corrector_tolerance", "a positive number"};
  if (!positive(max_modulus_change))
    return OptionProblem{"max_modulus_change", "a positive number"};
  if (!positive(watch_band)) return OptionProblem{"watch_band", "a positive number"};
  if (!(min_tangent_cosine > 0.0 && min_tangent_cosine < 1.0))
    return OptionProblem{"min_tangent_cosine", "a number in (0, 1)"};
  if (!(positive(location_tolerance) && location_tolerance < 1.0))
    return OptionProblem{"location_tolerance", "a number in (0, 1)"};
  if (!positive(trust_limit)) return OptionProblem{"trust_limit", "a positive number"};
  for (std::size_t i = 0; i < user_points.size(); ++i) {
    if (!std::isfinite(user_points[i]))
      return OptionProblem{"user_points", "finite values of the parameter"};
    for (std::size_t j = 0; j < i; ++j)
      if (user_points[j] == user_points[i])
        return OptionProblem{"user_points", "distinct values (" + format_double(user_points[i]) +
                                                " is given twice)"};
  }
  for (const auto& v : user_values)
    if (!std::isfinite(v.value)) return OptionProblem{"user_values", "finite values"};
  return nested("orbit.", orbit.validate());
}

Continuation::Continuation(const OdeSystem& system, int parameter, ContinuationOptions options)
    : system_(system), parameter_(parameter), options_(std::move(options)) {
  if (const auto problem = options_.validate())
    throw std::invalid_argument("continuation options: " + problem->message());
  if (!(options_.upper > options_.lower))
    throw std::invalid_argument("continuation: the upper bound must exceed the lower bound");
  if (options_.max_parameter_step <= 0.0)
    options_.max_parameter_step = (options_.upper - options_.lower) / options_.parameter_steps;
  if (parameter < 0 || parameter >= system.parameter_count())
    throw std::invalid_argument("continuation: no parameter with index " +
                                std::to_string(parameter));
  for (const auto& v : options_.user_values) {
    if (v.quantity == UserValue::Quantity::Period && !system.autonomous())
      throw std::invalid_argument("continuation: user value " + v.name +
                                  ": a forced system's period is the forcing's");
    if (v.quantity != UserValue::Quantity::Period && (v.state < 0 || v.state >= system.dimension()))
      throw std::invalid_argument("continuation: user value " + v.name + ": no state " +
                                  std::to_string(v.state));
  }
  requested_ = options_;
  // A forced system's problem is made by each run, with the start's period (the forcing's).
  if (system.autonomous()) {
    problem_ = std::make_unique<ShootingProblem>(system_, options_.orbit.shooting);
    problem_->record_samples(true);  // each point's scales and description from its own run
  }
}

double Continuation::corrector_tolerance() const {
  return attainable_tolerance(options_.corrector_tolerance, options_.orbit.newton.rtol_factor,
                              options_.orbit.shooting.flow, space_->sizes().maxCoeff());
}

Correction Continuation::correct_step(const PhaseSection& section, const Eigen::VectorXd& from,
                                      const Eigen::VectorXd& tangent, double step,
                                      const Eigen::VectorXd& guess,
                                      const Eigen::SparseMatrix<double>* chord,
                                      double expected) const {
  CorrectorOptions corrector;
  corrector.max_iterations = options_.max_corrector_iterations;
  corrector.max_chord_steps = options_.max_chord_steps;
  corrector.derivatives_first = predictions_land_;
  corrector.tolerance = corrector_tolerance();
  corrector.expected_residual = expected;
  return correct(*problem_, section, *space_, parameter_, corrector, from, tangent, step, guess,
                 chord);
}

namespace {

struct Growth {
  double segment = 0.0, monodromy = 0.0;
  // On half the segments (each pair j = 2k, 2k + 1 made one, m even): the largest of
  // |D^-1 M D|_inf over each pair's two matrices and their product, a lower bound of the growth
  // inside the merged segment. Infinite for an odd count.
  double halved = std::numeric_limits<double>::infinity();
};

// |D^-1 M D|_inf for each segment's M (the largest) and for their product, the monodromy.
Growth growth(const std::vector<Eigen::MatrixXd>& transitions, const Eigen::VectorXd& state_sizes) {
  // A state that stays at 0 on the orbit has no scale of its own: it gets a small one, so that
  // its row still counts (its own growth, in which the scale cancels).
  const double largest = state_sizes.size() ? state_sizes.cwiseAbs().maxCoeff() : 0.0;
  const Eigen::VectorXd sizes =
      state_sizes.cwiseAbs().cwiseMax(largest > 0.0 ? 1e-8 * largest : 1.0);
  const auto scaled_norm = [&](const Eigen::MatrixXd& M) {
    double norm = 0.0;  // the largest row sum of |M_ij| s_j / s_i
    for (int i = 0; i < M.rows(); ++i) {
      double row = 0.0;
      for (int j = 0; j < M.cols(); ++j) row += std::abs(M(i, j)) * sizes[j];
      norm = std::max(norm, row / sizes[i]);
    }
    return norm;
  };
  Growth g;
  Eigen::MatrixXd product;
  bool whole = true;
  for (const auto& M : transitions) {
    if (M.rows() != sizes.size() || M.cols() != sizes.size()) {  // a reduced block
      whole = false;
      continue;
    }
    g.segment = std::max(g.segment, scaled_norm(M));
    product = product.size() ? Eigen::MatrixXd(M * product) : M;
  }
  if (whole && product.size()) g.monodromy = scaled_norm(product);
  const std::size_t m = transitions.size();
  if (whole && m >= 2 && m % 2 == 0) {
    g.halved = g.segment;
    for (std::size_t j = 0; j < m; j += 2)
      g.halved = std::max(g.halved, scaled_norm(transitions[j + 1] * transitions[j]));
  }
  return g;
}

}  // namespace

ContinuationPoint Continuation::make_point(const Correction& c, const Eigen::VectorXd& tangent,
                                           int index, double step) const {
  const int N = problem_->unknowns(), n = problem_->dimension(), m = problem_->segments();
  ContinuationPoint p;
  p.index = index;
  p.parameter = c.y[N];
  p.unknowns = c.y.head(N);
  p.tangent = tangent;
  p.section = c.evaluation.section;
  p.step = step;
  p.iterations = c.iterations;
  PeriodicOrbit& o = p.orbit;
  o.state0 = c.y.head(n);
  o.period = problem_->period(c.y.head(N));
  o.segments = m;
  if (space_) {
    const Growth g = growth(c.evaluation.transitions, space_->sizes().head(n));
    o.segment_growth = g.segment;
    o.monodromy_growth = g.monodromy;
  }
  o.residual = c.residual;
  o.family_dimension = family_dimension_;
  o.parameters = c.evaluation.parameters;
  o.subspace = subspace_;
  o.floquet = shooting_floquet(*problem_, c.evaluation, o.state0, family_dimension_,
                               options_.orbit.floquet, subspace_);
  o.samples = c.evaluation.samples;
  o.newton.converged = true;
  o.newton.outcome = NewtonOutcome::Converged;
  o.newton.iterations = c.iterations;
  o.newton.reason = "corrector converged";
  return p;
}

std::optional<HopfPoint> Continuation::hopf_end(const Bifurcation& turn) const {
  // The turn is located where the orbit is smallest: nearly the equilibrium, its period nearly
  // 2 pi / omega. Accepted as the family's end only where the equilibrium there has that pair and
  // its Hopf point lies within 2% of the window of the turn, with the period within 5%.
  const double range = options_.upper - options_.lower;
  std::string why;
  auto hopf = hopf_point_near(system_, parameter_, space_->values_at(turn.parameter), turn.state0,
                              2 * std::numbers::pi / turn.period, 1e-4 * range, why);
  if (!hopf) return std::nullopt;
  if (std::abs(hopf->parameter - turn.parameter) > 0.02 * range ||
      std::abs(hopf->period - turn.period) > 0.05 * hopf->period)
    return std::nullopt;
  return hopf;
}

std::optional<ContinuationPoint> Continuation::point_on_bound(const ContinuationPoint& a,
                                                              const ContinuationPoint& b,
                                                              double bound) const {
  const int N = problem_->unknowns();
  return point_where(a, b, N, bound);
}

std::optional<ContinuationPoint> Continuation::point_where(const ContinuationPoint& a,
                                                           const ContinuationPoint& b, int k,
                                                           double value) const {
  const int N = problem_->unknowns();
  Eigen::VectorXd ya(N + 1), yb(N + 1);
  ya << a.unknowns, a.parameter;
  yb << b.unknowns, b.parameter;
  // A "tangent" whose arclength row is the unit row of y_k: the condition y_k - y_k(a) = step.
  const double w = space_->weights()[k];
  Eigen::VectorXd along = Eigen::VectorXd::Zero(N + 1);
  along[k] = 1.0 / (w * w);
  const double t = (value - ya[k]) / (yb[k] - ya[k]);
  const Correction c =
      correct_step(a.section, ya, along, value - ya[k], ya + t * (yb - ya), &chord_jacobian_);
  if (!c.converged) return std::nullopt;
  const Eigen::VectorXd tau =
      space_->tangent(problem_->jacobian(c.evaluation, true), c.y, a.tangent);
  // Its arclength from a along a's tangent, as location measures it.
  ContinuationPoint p = make_point(c, tau, a.index + 1, space_->dot(a.tangent, c.y - ya));
  // The linear condition holds to rounding; the value itself is exact.
  if (k == N) p.parameter = value;
  if (k == N - 1 && system_.autonomous()) {
    p.unknowns[k] = value;
    p.orbit.period = value;
  }
  return p;
}

std::optional<ContinuationPoint> Continuation::point_at(
    const ContinuationPoint& a, double s, std::string& why, const ContinuationPoint* b,
    const Eigen::SparseMatrix<double>* jacobian_b) const {
  const int N = problem_->unknowns();
  Eigen::VectorXd ya(N + 1);
  ya << a.unknowns, a.parameter;
  Eigen::VectorXd guess = ya + s * a.tangent;
  Eigen::SparseMatrix<double> chord = chord_jacobian_;
  if (b) {
    if (auto between = predict_between(*space_, a, *b, s, options_.min_tangent_cosine)) {
      guess = std::move(between->y);
      if (jacobian_b && jacobian_b->rows() == chord.rows() && jacobian_b->cols() == chord.cols())
        chord = (1.0 - between->fraction) * chord_jacobian_ + between->fraction * *jacobian_b;
    }
  }
  const Correction c = correct_step(a.section, ya, a.tangent, s, guess, &chord);
  if (!c.converged) {
    why = c.reason;
    return std::nullopt;
  }
  const Eigen::VectorXd tau =
      space_->tangent(problem_->jacobian(c.evaluation, true), c.y, a.tangent);
  return make_point(c, tau, a.index, s);
}

void Continuation::begin_run(const PeriodicOrbit& start) {
  // Each run chooses its integrator for itself, from the options as asked: BDF chosen for an
  // earlier run's stiff start does not carry over. (The shooting problem does, with the segments
  // a refinement gave it: the other half of a switched branch, AUTO's tor, took twice the time
  // refining again from one.)
  options_ = requested_;
  stiffness_.reset();
  FlowOptions& flow = options_.orbit.shooting.flow;
  if (options_.orbit.switch_when_stiff && flow.method != Method::BDF && start.period > 0.0 &&
      std::isfinite(start.period)) {
    options_.orbit.switch_when_stiff = false;  // measured: the branch's options say what it chose
    // The start's own measurement where it carries one (an orbit found with the switch on, or the
    // other half of a two-way run: the same period, two plain runs saved), else measured here.
    stiffness_ = start.stiffness ? start.stiffness
                                 : stiffness_of_guess(system_, flow, start.state0, start.parameters,
                                                      start.period);
    if (stiffness_) flow = after_stiffness(flow, *stiffness_);
  }
  if (system_.autonomous() && problem_->method() != flow.method) {
    problem_ = std::make_unique<ShootingProblem>(system_, options_.orbit.shooting);
    problem_->record_samples(true);
  }
}

Branch Continuation::run(const PeriodicOrbit& start, int direction,
                         const ContinuationCallbacks& callbacks,
                         const Eigen::VectorXd& initial_tangent) {
  return run_from(start, direction, callbacks, initial_tangent, Eigen::VectorXd());
}

Branch Continuation::run_from(const PeriodicOrbit& start, int direction,
                              const ContinuationCallbacks& callbacks,
                              const Eigen::VectorXd& initial_tangent,
                              const Eigen::VectorXd& sizes) {
  const Stopwatch started;
  begin_run(start);
  // A periodically forced system: the period is the forcing's, the start's, fixed along the
  // branch (the continued parameter must not change it); the unknowns are the segment states.
  if (!system_.autonomous()) {
    if (!(start.period > 0.0 && std::isfinite(start.period)))
      throw std::invalid_argument("continuation: a forced system's start needs its period");
    problem_ = std::make_unique<ShootingProblem>(system_, options_.orbit.shooting, start.period);
    problem_->record_samples(true);
  }
  Branch branch;
  branch.parameter_name = system_.parameter_names()[parameter_];
  branch.parameter = parameter_;
  branch.state_names = system_.state_names();
  branch.options = options_;  // after begin_run: the method used
  branch.start_values = start.parameters;
  problem_->reset_statistics();
  predictions_land_ = false;
  guess_residual_ = std::numeric_limits<double>::infinity();  // unknown: the first step learns it
  auto finish = [&](StopReason stop, const std::string& reason) {
    branch.stop = stop;
    branch.stop_reason = reason;
    branch.flow = problem_->statistics();
    branch.across_evaluations = problem_->across_evaluations();
    branch.split_evaluations = problem_->split_evaluations();
    branch.stiffness = stiffness_;
    branch.seconds = started.seconds();
    return branch;
  };
  const int N = problem_->unknowns();
  if (start.parameters.size() == 0)
    throw std::invalid_argument("continuation: the starting orbit carries no parameter values");
  system_.check_parameters(start.parameters);
  subspace_ = start.subspace;
  // A symmetric orbit that the parameter does not move: each point integrates only the block
  // across its subspace (shooting.hpp); checked at every point, the whole computation otherwise.
  problem_->use_symmetry(options_.orbit.use_symmetry ? subspace_ : InvariantSubspace());
  space_ = std::make_unique<BranchSpace>(system_, *problem_, parameter_, start.parameters,
                                         options_.upper - options_.lower,
                                         options_.orbit.newton.rank_tolerance);
  const BranchSpace& space = *space_;
  try {
    space_->reset_scales(start.state0, start.period, options_.orbit.transient_flow, &start.samples);
    if (sizes.size()) space_->include_sizes(sizes);
  } catch (const IntegrationError& e) {
    return finish(StopReason::StartFailed,
                  std::string("the starting orbit cannot be integrated: ") + e.what());
  }

  // The starting point, corrected at its parameter value.
  const double p0 = system_.parameter(start.parameters, parameter_);
  const PhaseSection section0 = space.section(start.state0, p0);
  Eigen::VectorXd y0(N + 1);
  try {
    y0.head(N) = problem_->unknowns_from(start.state0, start.parameters, start.period);
  } catch (const IntegrationError& e) {
    return finish(StopReason::StartFailed,
                  std::string("the starting orbit cannot be integrated: ") + e.what());
  }
  y0[N] = p0;
  Eigen::VectorXd along_parameter = Eigen::VectorXd::Zero(N + 1);
  along_parameter[N] = 1.0 / space.weights()[N];  // unit in the scaled norm
  const Correction c0 = correct_step(section0, y0, along_parameter, 0.0, y0, nullptr);
  if (!c0.converged)
    return finish(StopReason::StartFailed, "the starting orbit does not converge: " + c0.reason);
  // A continuum of orbits persists along the branch: its dimension is decided once, here, not
  // at each point (near a branch point the Jacobian is nearly singular too, for other reasons).
  family_dimension_ =
      rank_deficiency(problem_->jacobian(c0.evaluation), options_.orbit.newton.rank_tolerance);
  Eigen::VectorXd tau;
  if (initial_tangent.size() == N + 1) {
    // The start's own tangent, oriented along the one given: a switched branch starts a step off
    // its event, where the given direction (the event's) is only first-order right, and its
    // parameter component, zero at a pitchfork, must have the sign the branch really has there
    // (else the next point's sign change is taken for a fold).
    tau = space.tangent(problem_->jacobian(c0.evaluation, true), c0.y, initial_tangent);
  } else {
    tau = space.tangent(problem_->jacobian(c0.evaluation, true), c0.y, direction * along_parameter);
  }
  chord_jacobian_ = problem_->jacobian(c0.evaluation, true);
  jacobian_before_ = Eigen::SparseMatrix<double>();
  OrbitNode first;
  static_cast<ContinuationPoint&>(first) = make_point(c0, tau, 0, 0.0);

  Run run(*this);
  driver::Options o = driver::step_options(options_);
  o.location_retries = 3;
  // Growth by at most 1.2 after a step the multipliers' motion shortened: near a branch point
  // their motion grows faster than the step (on the anti-phase k-branch a step grown 1.5 times
  // after such a retry was retried again at least 8 times of its 15 retries; at 1.2, 8 retries
  // and 65 points instead of 15 and 70, 13% less time).
  o.rule = {2, 1.5, 1.2, 5, 0.6};
  driver::Callbacks<OrbitNode, Bifurcation> cb;
  cb.on_point = [&](const OrbitNode& p) {
    if (callbacks.on_point) callbacks.on_point(p);
  };
  cb.on_event = callbacks.on_event;
  cb.stop_requested = callbacks.stop_requested;
  auto result = driver::continuation(run, std::move(first), o, cb);
  // A point's samples serve its callback and scales, not the branch kept (801 states a point).
  for (auto& p : result.points) {
    p.orbit.samples = PeriodSamples{};
    branch.points.push_back(std::move(static_cast<ContinuationPoint&>(p)));
  }
  branch.events = std::move(result.events);
  // The segments the branch ended on (refined where the corrector kept failing; each point
  // records its own).
  branch.options.orbit.shooting.segments = problem_->segments();
  const auto count = [&](driver::Cause c) { return result.rejected[static_cast<int>(c)]; };
  branch.rejected.corrector = count(driver::Cause::Corrector) + count(driver::Cause::Edge);
  branch.rejected.turn = count(driver::Cause::Turn);
  branch.rejected.multipliers = count(driver::Cause::Multipliers);
  branch.rejected.location = count(driver::Cause::Location);
  branch.hopf_end = run.hopf_end;
  return finish(result.stop, result.message + run.past_note());
}

// One way along a branch of periodic orbits, as the driver's problem (driver.hpp): the pieces of
// the header's comment. The chord Jacobians of the last two accepted points stay with the
// Continuation (chord_jacobian_, jacobian_before_), replaced only when a point is accepted.
Continuation::Run::Run(Continuation& c)
    : c_(c),
      N_(c.problem_->unknowns()),
      carries_crossings_(c.system_.switching_count() > 0 &&
                         dynamic_cast<const HybridSystem*>(&c.system_) != nullptr) {}

double Continuation::Run::limit_step(const OrbitNode& a, double ds) const {
  return parameter_limited_step(ds, std::abs(a.tangent[N_]), c_.options_);
}

driver::Attempt<OrbitNode> Continuation::Run::step(const OrbitNode* before, const OrbitNode& a,
                                                   double ds) {
  if (before && before->unknowns.size() != a.unknowns.size()) before = nullptr;  // refined at a
  ShootingProblem& problem = *c_.problem_;
  const BranchSpace& space = *c_.space_;
  const ContinuationOptions& options = c_.options_;
  driver::Attempt<OrbitNode> attempt;
  Eigen::VectorXd ya(N_ + 1);
  ya << a.unknowns, a.parameter;
  // The quasi-Newton steps start from the Jacobian extrapolated along the branch from the last
  // two points (when they share a's section): its error is then O(ds^2), not O(ds).
  Eigen::SparseMatrix<double> chord = c_.chord_jacobian_;
  if (before && before->section == a.section && a.step > 0.0 &&
      c_.jacobian_before_.rows() == chord.rows() && c_.jacobian_before_.cols() == chord.cols())
    chord = c_.chord_jacobian_ + (ds / a.step) * (c_.chord_jacobian_ - c_.jacobian_before_);
  const Eigen::VectorXd predicted =
      predict(space, before, a, ds, options.curved_predictor, options.min_tangent_cosine);
  // A prediction past the bound, where the last one landed: the point on the bound at once,
  // not first the step's point beyond it and then the bound's (one correction instead of two:
  // 1 of the fast preset's 89 on the anti-phase k-branch). Its multipliers are watched as a
  // step's; too far, the step is retried shorter as any other, until its prediction falls
  // short of the bound. Not where predictions miss: the branch may turn before the bound (the
  // in-phase s-branch shrinks into its Hopf point at s = 2.4e-9, and a point at s = 0 was
  // sought in vain: 5 integrations).
  const double predicted_bound = std::clamp(predicted[N_], options.lower, options.upper);
  if (c_.predictions_land_ && predicted_bound != predicted[N_] && a.parameter > options.lower &&
      a.parameter < options.upper) {
    ContinuationPoint ahead;
    ahead.unknowns = predicted.head(N_);
    ahead.parameter = predicted[N_];
    if (auto at_bound = c_.point_on_bound(a, ahead, predicted_bound)) {
      attempt.point.emplace();
      static_cast<ContinuationPoint&>(*attempt.point) = std::move(*at_bound);
      attempt.point->iterations = 0;  // the step rule's: the run ends here
      attempt.on_edge = true;
      return attempt;
    }
  }
  Correction c =
      c_.correct_step(a.section, ya, a.tangent, ds, predicted, &chord, c_.guess_residual_);
  c_.predictions_land_ = c.converged && c.chord_steps == 0 && c.iterations == 0;
  if (std::isfinite(c.guess_residual)) c_.guess_residual_ = c.guess_residual;
  if (!c.converged) {
    attempt.why = c.reason;
    return attempt;
  }
  // A branch in its symmetric subspace stays there exactly, its tangents too.
  const bool in_subspace = problem.keep_in_subspace(c.y, space.values_at(c.y[N_]));
  const Eigen::VectorXd& y = c.y;
  // The section stays while the flow crosses it well (the angle in the scaled norm): kept, the
  // points lie on one smooth curve, which the predictor and the extrapolated Jacobian follow.
  const int n = problem.dimension();
  const Eigen::VectorXd zb = y.head(n);
  const Eigen::VectorXd w = space.weights().head(n);
  const Eigen::VectorXd flow_b = w.asDiagonal() * c_.system_.rhs(0.0, zb, space.values_at(y[N_]));
  const Eigen::VectorXd flow_ref = w.cwiseInverse().asDiagonal() * a.section.normal;
  const double crossing = flow_ref.normalized().dot(flow_b.normalized());
  if (crossing < 0.9) problem.move_to_section(c.evaluation, y.head(N_), space.section(zb, y[N_]));
  Eigen::SparseMatrix<double> jacobian_b = problem.jacobian(c.evaluation, true);
  Eigen::VectorXd tau_b = space.tangent(jacobian_b, y, a.tangent);
  if (in_subspace) problem.project_on_subspace(tau_b);
  attempt.point.emplace();
  static_cast<ContinuationPoint&>(*attempt.point) = c_.make_point(c, tau_b, a.index + 1, ds);
  attempt.point->jacobian = std::move(jacobian_b);
  if (problem.segments() > options.orbit.shooting.segments)
    attempt.point->halved_growth =
        growth(c.evaluation.transitions, space.sizes().head(problem.dimension())).halved;
  return attempt;
}

double Continuation::Run::turn_cosine(const OrbitNode& a, const OrbitNode& b) const {
  if (b.jacobian.rows() == 0) return 1.0;  // on the bound already: the run ends there
  Eigen::VectorXd y(N_ + 1);
  y << b.unknowns, b.parameter;
  return c_.space_->turn_cosine(b.tangent, a.tangent, y);
}

driver::Screen Continuation::Run::screen(const OrbitNode* before, const OrbitNode& a,
                                         const OrbitNode& b, double ds) {
  // A step whose multipliers could not be paired with confidence, or moved too far near the
  // circle, is rejected after its whole cost: the retry, and the step after an accepted one,
  // aim below both limits at the rates just seen.
  if (past_) return {};
  tracked_ = track(before, a, b);
  tracked_unknowns_ = b.unknowns;
  tracked_parameter_ = b.parameter;
  const MultiplierMotion motion = multiplier_motion(tracked_, ds, c_.options_);
  return {motion.too_far, motion.aim, "multipliers moved too far"};
}

bool Continuation::Run::outside(const OrbitNode& b) const {
  return b.parameter < c_.options_.lower || b.parameter > c_.options_.upper;
}

std::optional<OrbitNode> Continuation::Run::onto_edge(const OrbitNode& a, const OrbitNode& b) {
  // The last point lies on the bound, never beyond it: a point past the bound gives way to the
  // branch's point at the bound (the parameter fixed there instead of the arclength), and the
  // events between a and it are the branch's last.
  const double bound = std::clamp(b.parameter, c_.options_.lower, c_.options_.upper);
  auto at = c_.point_on_bound(a, b, bound);
  if (!at) return std::nullopt;
  OrbitNode node;
  static_cast<ContinuationPoint&>(node) = std::move(*at);
  return node;
}

driver::Found<Bifurcation> Continuation::Run::detect(const OrbitNode* before, const OrbitNode& a,
                                                     const OrbitNode& b) {
  driver::Found<Bifurcation> found;
  const ContinuationOptions& options = c_.options_;
  if (options.detect_bifurcations && !past_) {
    // Location probes along a's tangent in a's section, guessed on the cubic through a and b
    // and corrected from the Jacobian interpolated between theirs (a's alone where b lies on the
    // bound: its Jacobian is not in a's section's step).
    // The screen's pairing where b is the point it saw (not moved onto the bound since).
    const bool same = b.parameter == tracked_parameter_ &&
                      b.unknowns.size() == tracked_unknowns_.size() &&
                      b.unknowns == tracked_unknowns_;
    const TrackedMultipliers tracked = same ? tracked_ : track(before, a, b);
    const Eigen::SparseMatrix<double>* jacobian_b = b.jacobian.rows() ? &b.jacobian : nullptr;
    const Locator locator = [&](BifurcationType type, int multiplicity, std::complex<double> mu_a,
                                std::complex<double> mu_b, bool beside_fold) {
      Bifurcation e = locate(
          a, b, type, multiplicity, mu_a, mu_b, options.location_tolerance,
          0.01 * (options.upper - options.lower),
          [&](double s, std::string& why) { return c_.point_at(a, s, why, &b, jacobian_b); },
          beside_fold);
      c_.refine_branch_point(e, a, b);
      return e;
    };
    found.events = sympathy::detect(tracked, a, b, c_.trust_limit(), locator,
                                    [&](const Bifurcation& turn) { return !!hopf_end_of(turn); });
    // A fold without a multiplier seen through +1 is tried again on shorter steps too: a fold of
    // cycles has one there, and a long step may have let it pass out and back (AUTO's tor near
    // its homoclinic orbit: the largest multiplier 5e5 at T 47.4, 1 at the fold at T 49.36,
    // 9.5e5 at T 50.9, one step apart). Not where the orbits shrink into an equilibrium: that
    // turn has none to find, and is the family's end (ends).
    for (const auto& e : found.events)
      found.unlocated |=
          !e.located() || (e.trust == EventTrust::NoCrossingMultiplier && !hopf_end_of(e));
  }
  if (!options.user_points.empty()) {  // AUTO's UZ, among the step's events along it
    auto passed = c_.user_points_between(a, b);
    found.events.insert(found.events.end(), passed.begin(), passed.end());
  }
  // AUTO's UZ and UZSTOP on a quantity of the orbits: the first stop of the step ends the branch
  // there (ends).
  stop_at_.reset();
  for (auto& [event, stop] :
       c_.user_values_between(a, b, b.jacobian.rows() ? &b.jacobian : nullptr)) {
    if (stop && (!stop_at_ || event.arclength < stop_at_->first))
      stop_at_.emplace(event.arclength, event.note);
    found.events.push_back(std::move(event));
  }
  std::stable_sort(found.events.begin(), found.events.end(),
                   [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
  return found;
}

namespace {

PeriodRecord record_of(const OrbitNode& p) {
  return {p.parameter, p.orbit.period, p.orbit.floquet.trivial_error};
}

}  // namespace

std::optional<driver::Ending> Continuation::Run::ends(const OrbitNode& a, const OrbitNode& b,
                                                      std::vector<Bifurcation>& events) {
  const auto name = [&] { return c_.system_.parameter_names()[c_.parameter_]; };
  // A value the branch was asked to stop at, passed in this step: the events beyond it dropped,
  // b not kept (the branch's orbit there is the event's).
  if (stop_at_) {
    const double s = stop_at_->first;
    const std::string note = stop_at_->second;
    stop_at_.reset();
    std::erase_if(events, [&](const Bifurcation& e) { return e.arclength > s; });
    return driver::Ending{driver::Stop::UserValue, "reached the value asked for: " + note, false};
  }
  // A hybrid orbit's crossings changed in the step: a grazing, located, ends the branch (its
  // flow has no derivative there); the step's events beyond it dropped, b not kept.
  if (carries_crossings_) {
    try {
      if (crossings_.empty()) crossings_ = c_.crossings_of(a);
      crossings_b_ = c_.crossings_of(b);
    } catch (const IntegrationError& e) {
      // The plain run of b's orbit meets a tangency or sliding itself (NonsmoothFlowError).
      return driver::Ending{driver::Stop::Nonsmooth,
                            std::string("the orbit at ") + name() + " = " +
                                format_double(b.parameter) + " is not smooth: " + e.what(),
                            false};
    }
    if (crossings_b_ != crossings_) {
      const CrossingChange g = c_.crossing_change(a, b, crossings_, crossings_b_,
                                                  b.jacobian.rows() ? &b.jacobian : nullptr);
      std::erase_if(events, [&](const Bifurcation& e) { return e.arclength > g.arclength; });
      char where[160];
      std::snprintf(where, sizeof where, "%s = %.10g (probes %.2g apart)", name().c_str(),
                    g.parameter, 2 * g.uncertainty);
      return driver::Ending{driver::Stop::Nonsmooth,
                            std::string("grazing near ") + where + ": " + g.note +
                                "; the orbits' flow has no derivative there, so the branch ends",
                            false};
    }
  }
  if (path_.empty()) path_.push_back(y_of(a));
  if (periods_.empty()) periods_.push_back(record_of(a));
  // A family approaching a homoclinic orbit: ended there, b kept (it is as good as any before).
  // Within 1e-4 of the parameter (relative, at least 1e-4): on AUTO's pp2 the period doubles
  // from 38 to 76 within it, before the orbits' monodromies grow past what the multipliers
  // resolve (their trivial error 1e-3 at T 94); fhn's canard grows it 1.6 times.
  // Or seen through its orbits, which are no longer resolved while the period grows (AUTO's pen).
  periods_.push_back(record_of(b));
  // A stop asked for at a longer period (AUTO's UZSTOP on PERIOD: pen's families to T = 30,
  // ab's to T = 1000) goes on toward it: the homoclinic approach is where a run would otherwise
  // go on without end, and this one has its end. Past the approach no bifurcation is sought
  // (past_: the multipliers and the parameter's motion are noise there); the corrector
  // alone carries the branch, and its stop at the period rests on the corrector, as every user
  // value does.
  const bool asked = std::ranges::any_of(c_.options_.user_values, [&](const UserValue& v) {
    return v.stop && v.quantity == UserValue::Quantity::Period && v.value > b.orbit.period;
  });
  const auto homoclinic =
      homoclinic_approach(periods_, 1e-4 * std::max(1.0, std::abs(b.parameter)));
  const auto unresolved = homoclinic ? std::nullopt : unresolved_approach(periods_);
  periods_.pop_back();
  if ((homoclinic || unresolved) && c_.system_.autonomous()) {
    if (asked) {
      if (!past_) past_ = record_of(b);
    } else {
      const HomoclinicApproach& h = homoclinic ? *homoclinic : *unresolved;
      char what[320];
      std::snprintf(what, sizeof what,
                    "approaching a homoclinic orbit near %s = %.10g: the period grew from %.6g to "
                    "%.6g while %s moved by %.2g%s; stopped there",
                    name().c_str(), h.parameter, h.from_period, h.to_period, name().c_str(),
                    h.parameter_spread,
                    homoclinic ? ""
                               : " and the orbits' multipliers were not resolved "
                                 "(trivial-multiplier errors above 1e-2)");
      return driver::Ending{driver::Stop::Homoclinic, what, true};
    }
  }
  // A branch that turned back without a multiplier at +1 and now retraces itself: b lies on one
  // of the branch's chords before the turn (driver::on_chord). Stopped there, b not kept.
  if (turn_) {
    const Eigen::VectorXd yb = y_of(b);
    const auto dot = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
      return c_.space_->dot(u, v);
    };
    for (std::size_t k = 1; k <= turn_->first && k < path_.size(); ++k) {
      if (driver::on_chord(yb, path_[k - 1], path_[k], dot))
        return driver::Ending{driver::Stop::TurnedBack,
                              "turned back at " + name() + " = " + format_double(turn_->second) +
                                  " without a multiplier at +1 and retraced itself: stopped there",
                              false};
    }
  }
  // A fold without its multiplier at +1 in this step: the branch turned back.
  const auto turn = std::find_if(events.begin(), events.end(), [](const auto& e) {
    return e.trust == EventTrust::NoCrossingMultiplier;
  });
  if (turn == events.end()) return std::nullopt;
  // Where the orbits shrink into an equilibrium the branch turns at its Hopf point: that
  // point, located on the equilibria, ends the family (and the turn is no fold to report).
  if (const auto& hopf = hopf_end_of(*turn)) {
    events.erase(turn);
    hopf_end = hopf;
    char omega[96];
    std::snprintf(omega, sizeof omega, "omega %.10g, period 2 pi / omega = %.10g", hopf->omega,
                  hopf->period);
    return driver::Ending{driver::Stop::HopfPoint,
                          "ended at the Hopf point of the equilibrium at " + name() + " = " +
                              format_double(hopf->parameter) + " (" + omega + ", " +
                              describe_criticality(hopf->lyapunov) +
                              "): the orbits shrink into the equilibrium there",
                          false};
  }
  // Elsewhere the branch goes on through the turn (reported, untrusted): a fold whose multiplier
  // the pairing missed, or the tangent's parameter component flipping within the noise where the
  // branch is nearly vertical (AUTO's fhn: a canard at a = 0.4305, multiplier 23), is no end. It
  // stops where it retraces itself (above).
  if (!turn_) turn_ = {path_.size() - 1, turn->parameter};
  return std::nullopt;
}

const std::optional<HopfPoint>& Continuation::Run::hopf_end_of(const Bifurcation& turn) {
  const Eigen::Vector2d key(turn.parameter, turn.period);
  if (!hopf_asked_ || hopf_asked_->first != key) hopf_asked_.emplace(key, c_.hopf_end(turn));
  return hopf_asked_->second;
}

Eigen::VectorXd Continuation::Run::y_of(const OrbitNode& p) const {
  Eigen::VectorXd y(N_ + 1);
  y << p.unknowns, p.parameter;
  return y;
}

void Continuation::Run::accept(OrbitNode& b) {
  if (carries_crossings_) crossings_ = std::move(crossings_b_);
  path_.push_back(y_of(b));
  periods_.push_back(record_of(b));
  c_.jacobian_before_ = std::move(c_.chord_jacobian_);
  c_.chord_jacobian_ = std::move(b.jacobian);
  b.jacobian = Eigen::SparseMatrix<double>();
  // Scales follow the amplitudes met so far; the tangent stays a unit vector in them.
  try {
    c_.space_->widen_scales(b.orbit.state0, b.orbit.parameters, b.orbit.period,
                            c_.options_.orbit.transient_flow, &b.orbit.samples);
  } catch (const IntegrationError&) {
    // keep the scales as they are
  }
  if (!keeps_samples()) b.orbit.samples = PeriodSamples{};
  b.tangent /= std::sqrt(c_.space_->dot(b.tangent, b.tangent));
  // Segments given back where the orbits no longer need them, as AUTO re-meshes both ways: a
  // refinement at a canard or a spike (AUTO's fhn, ab at p2 = 16) otherwise ran the rest of the
  // branch on 4 segments where one resolves it. b is re-sampled onto half (each new segment's
  // start is an old one's), corrected and its tangent recomputed, as a refinement does.
  // Past the homoclinic approach (past_) the segments only grow with the period.
  const int m = c_.problem_->segments();
  if (past_) {
    if (b.orbit.period / m > 0.75 * failed_duration_ && 2 * m <= kMostSegmentsPast)
      resample(b, 2 * m);
    return;
  }
  resolved_points_ = b.halved_growth < kHalvedGrowth ? resolved_points_ + 1 : 0;
  if (resolved_points_ >= kResolvedPoints) {
    resolved_points_ = 0;
    resample(b, m / 2);
  }
}

bool Continuation::Run::refine(OrbitNode& a, const std::string&) {
  // Where the corrector keeps failing, an orbit whose solutions grow fast along the period (a
  // canard, strongly unstable orbits: AUTO's fhn and ab) is resolved on twice the segments, up
  // to kMostSegments, and the step tried again. (More segments on every failure, or wherever a
  // segment's growth passes a limit, also let branches approaching a homoclinic orbit, AUTO's
  // pp2 and tor, run on toward infinite period at a growing cost.) The corrector's failure is
  // the criterion, not the segment's growth: one segment failed at a growth of 1.3e4 (AUTO's ab,
  // p2 = 15) where others converge at 7e5 (fhn) and 1.9e6 (pp2), all at rtol 5e-12.
  const int m = c_.problem_->segments();
  if (!(c_.system_.autonomous() && 2 * m <= (past_ ? kMostSegmentsPast : kMostSegments) &&
        resample(a, 2 * m)))
    return false;
  failed_duration_ = std::min(failed_duration_, a.orbit.period / m);
  return true;
}

bool Continuation::Run::resample(OrbitNode& a, int segments) {
  // The point re-sampled on `segments` segments (each segment's start from one integration),
  // corrected on the hyperplane normal to its tangent, its Jacobian and tangent recomputed; the
  // count recorded in each point (orbit.segments). False, and nothing changed, where it does not
  // correct.
  const int m = c_.problem_->segments();
  if (segments == m) return false;
  std::unique_ptr<ShootingProblem> old_problem = std::move(c_.problem_);
  std::unique_ptr<BranchSpace> old_space = std::move(c_.space_);
  const auto restore = [&] {
    c_.problem_ = std::move(old_problem);
    c_.space_ = std::move(old_space);
    return false;
  };
  ShootingOptions shooting = c_.options_.orbit.shooting;
  shooting.segments = segments;
  try {
    c_.problem_ = std::make_unique<ShootingProblem>(c_.system_, shooting);
    c_.problem_->record_samples(true);
    c_.problem_->use_symmetry(c_.options_.orbit.use_symmetry ? c_.subspace_ : InvariantSubspace());
    c_.space_ = std::make_unique<BranchSpace>(
        c_.system_, *c_.problem_, c_.parameter_, a.orbit.parameters,
        c_.options_.upper - c_.options_.lower, c_.options_.orbit.newton.rank_tolerance);
    c_.space_->reset_scales(a.orbit.state0, a.orbit.period, c_.options_.orbit.transient_flow);
    c_.space_->include_sizes(old_space->sizes());
    const int N = c_.problem_->unknowns();
    Eigen::VectorXd y(N + 1);
    // The new segments' starts from the old ones: on more segments each integrated over one new
    // segment at most; on fewer, every old one that starts a new segment kept as it is.
    const int n_old = c_.problem_->dimension();
    const int kept = segments % m == 0 ? m : m % segments == 0 ? segments : 0;
    Eigen::MatrixXd starts(n_old, kept);
    for (int j = 0; j < kept; ++j)
      starts.col(j) = a.unknowns.segment(j * (m / kept) * n_old, n_old);
    y.head(N) =
        kept ? c_.problem_->unknowns_from_starts(starts, a.orbit.parameters, a.orbit.period)
             : c_.problem_->unknowns_from(a.orbit.state0, a.orbit.parameters, a.orbit.period);
    y[N] = a.parameter;
    // The old tangent in the new unknowns (the first segment's start, the period and the parameter
    // mean the same in both; the new segments' starts get 0): the correction stays on the
    // hyperplane through the point normal to it, as the step's own does. (At a fixed parameter it
    // failed where the branch is vertical, as on AUTO's fhn canard, where that Jacobian is
    // singular.) It also orients the new tangent.
    const int n = c_.problem_->dimension(), N_old = N_;
    Eigen::VectorXd along = Eigen::VectorXd::Zero(N + 1);
    along.head(n) = a.tangent.head(n);
    along[N - 1] = a.tangent[N_old - 1];
    along[N] = a.tangent[N_old];
    const Correction c = c_.correct_step(a.section, y, along, 0.0, y, nullptr);
    if (!c.converged) return restore();
    Eigen::SparseMatrix<double> jacobian = c_.problem_->jacobian(c.evaluation, true);
    const Eigen::VectorXd tau = c_.space_->tangent(jacobian, c.y, along);
    OrbitNode refined;
    static_cast<ContinuationPoint&>(refined) = c_.make_point(c, tau, a.index, a.step);
    if (!keeps_samples()) refined.orbit.samples = PeriodSamples{};
    a = std::move(refined);
    N_ = N;
    c_.chord_jacobian_ = std::move(jacobian);
    c_.jacobian_before_ = Eigen::SparseMatrix<double>();
    c_.predictions_land_ = false;
    c_.guess_residual_ = std::numeric_limits<double>::infinity();
    path_.clear();  // unknowns of another size: the retrace check starts again
    turn_.reset();
    resolved_points_ = 0;
    return true;
  } catch (const IntegrationError&) {
    return restore();
  }
}

std::string Continuation::Run::past_note() const {
  if (!past_) return "";
  const std::string name = c_.system_.parameter_names()[c_.parameter_];
  return "; past its homoclinic approach (from T = " + format_number(past_->period) + ", " + name +
         " = " + format_double(past_->parameter) +
         ") the branch went on toward the period asked for, its orbits' multipliers unresolved: "
         "no bifurcation was sought beyond";
}

std::string Continuation::Run::edge_message(const OrbitNode&) const {
  return "reached the parameter bound";
}

}  // namespace sympathy
