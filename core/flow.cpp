// The flow's step loop (see flow.hpp): steep-zone bands and step caps, restarts at switching
// surfaces and outputs inside a step, on whichever integrator the options choose (the SUNDIALS
// side of each is in flow_cvodes.cpp, flow_augmented.cpp and flow_erk.cpp, behind
// flow_stepper.hpp).
#include "sympathy/core/flow.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "flow_stepper.hpp"
#include "sympathy/core/saltation.hpp"

namespace sympathy {

std::string to_string(Method m) {
  switch (m) {
    case Method::BDF:
      return "BDF";
    case Method::Adams:
      return "Adams";
    case Method::ERK:
      return "ERK";
  }
  return "?";
}
std::string to_string(Sensitivities s) {
  return s == Sensitivities::ForwardModule ? "forward module" : "augmented";
}
std::string to_string(ExplicitTable t) {
  return t == ExplicitTable::DormandPrince ? "Dormand-Prince 5(4)" : "Verner 6(5)";
}
std::string to_string(LinearSolver s) {
  switch (s) {
    case LinearSolver::Automatic:
      return "automatic";
    case LinearSolver::Dense:
      return "dense";
    case LinearSolver::KLU:
      return "KLU";
    case LinearSolver::Structured:
      return "structured";
  }
  return "?";
}

LinearSolver resolved_linear_solver(const OdeSystem& system, const FlowOptions& options) {
  if (options.linear_solver != LinearSolver::Automatic) return options.linear_solver;
  if (options.derivatives != Derivatives::Model) return LinearSolver::Dense;
  const auto structure = system.low_rank_structure();
  return structure && structure->dimension > 2 * (structure->rank() + 3) ? LinearSolver::Structured
                                                                         : LinearSolver::Dense;
}

OptionCheck FlowOptions::validate() const {
  // CVODES itself refuses tolerances near the unit roundoff ("too much accuracy requested").
  if (!(rtol >= 1e-14 && rtol < 1.0)) return OptionProblem{"rtol", "a number in [1e-14, 1)"};
  if (!positive(atol)) return OptionProblem{"atol", "a positive number"};
  if (max_steps < 1) return OptionProblem{"max_steps", "a positive integer"};
  if (!non_negative(max_step))
    return OptionProblem{"max_step", "0 (no limit) or a positive number"};
  if (!(steep_step_fraction > 0.0 && steep_step_fraction < 2.0 / 3.0))
    return OptionProblem{"steep_step_fraction", "a number in (0, 2/3)"};
  // An explicit method has no sensitivity module: its columns are part of the integrated state.
  if (method == Method::ERK && sensitivities != Sensitivities::Augmented)
    return OptionProblem{"sensitivities",
                         "Augmented with method ERK (an explicit method integrates the variational "
                         "equations appended to the state)"};
  if (sensitivities == Sensitivities::Augmented && derivatives != Derivatives::Model)
    return OptionProblem{"derivatives",
                         "Model with augmented sensitivities (the variational equations are the "
                         "system's own derivatives)"};
  return std::nullopt;
}

FlowStatistics& FlowStatistics::operator+=(const FlowStatistics& o) {
  calls += o.calls;
  steps += o.steps;
  rhs_evaluations += o.rhs_evaluations;
  jacobian_evaluations += o.jacobian_evaluations;
  variational_evaluations += o.variational_evaluations;
  linear_setups += o.linear_setups;
  error_test_failures += o.error_test_failures;
  nonlinear_iterations += o.nonlinear_iterations;
  steep_roots += o.steep_roots;
  switchings += o.switchings;
  return *this;
}

Flow::Flow(const OdeSystem& system, FlowOptions options)
    : system_(system), options_(options), call_(std::make_unique<detail::FlowCall>(system)) {
  options_.linear_solver = resolved_linear_solver(system_, options_);
  if (const auto problem = options_.validate())
    throw std::invalid_argument("flow options: " + problem->message());
  if (options_.method == Method::ERK)
    stepper_ = detail::make_erk_stepper(*call_, options_);
  else if (options_.sensitivities == Sensitivities::Augmented)
    stepper_ = detail::make_augmented_cvode_stepper(*call_, options_);
  else
    stepper_ = detail::make_cvodes_stepper(*call_, options_);
  // Steep zones and switching surfaces are set up by each call (start), from its parameter values.
  dz_scratch_.resize(system_.dimension());
}

Flow::~Flow() = default;

// Zones follow the call's parameter values (a zone's width may depend on them).
void Flow::configure_zones() {
  const int n = system_.dimension();
  zones_ = options_.resolve_steep_zones ? system_.steep_zones(call_->values.data())
                                        : std::vector<SteepZone>{};
  levels_.clear();
  for (const auto& zone : zones_) {
    if (zone.component < 0 || zone.component >= n || !(zone.width > 0.0) ||
        !(zone.scale > zone.width))
      throw std::invalid_argument("invalid steep zone of the system");
    std::vector<double> levels{zone.scale};
    while (levels.back() >= zone.width) levels.push_back(levels.back() / 3.0);
    levels_.push_back(std::move(levels));
  }
}

void Flow::start(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                 std::span<const int> initial_components, std::span<const int> parameters) {
  const int n = system_.dimension();
  const int sensitivity_columns = static_cast<int>(initial_components.size() + parameters.size());
  for (int c : initial_components)
    if (c < 0 || c >= n)
      throw std::invalid_argument("flow: no state component " + std::to_string(c));
  for (int k : parameters)
    if (k < 0 || k >= system_.parameter_count())
      throw std::invalid_argument("flow: no parameter with index " + std::to_string(k));
  system_.check_parameters(p);
  if (z0.size() != n)
    throw std::invalid_argument("initial state has " + std::to_string(z0.size()) +
                                " entries; the system has " + std::to_string(n));
  if (!z0.allFinite()) throw std::invalid_argument("initial state is not finite");
  if (sensitivity_columns > 0) {
    if (!system_.differentiable())
      throw std::invalid_argument("sensitivities need a differentiable system");
    if (system_.switching_count() > 0 && !call_->hybrid)
      throw std::invalid_argument(
          "sensitivities across switching surfaces need a piecewise-smooth system that declares "
          "the surfaces' gradients and its resets (HybridSystem)");
    if (options_.derivatives == Derivatives::DifferenceQuotients && !parameters.empty())
      throw std::invalid_argument(
          "parameter sensitivities need the system's derivatives, not difference quotients");
  }
  auto& call = *call_;
  t_ = t0;
  call.callback_error = nullptr;
  call.last_error.clear();
  call.values = p;
  call.columns = sensitivity_columns;
  call.parameters.assign(parameters.begin(), parameters.end());
  configure_zones();
  call.root_directions.clear();
  if (call_->hybrid)
    for (int i = 0; i < system_.switching_count(); ++i)
      call.root_directions.push_back(call_->hybrid->crossing_direction(i));
  // Initial sensitivities: unit vectors in the state columns, zero in the parameter columns.
  seeds_ = Eigen::MatrixXd::Zero(n, sensitivity_columns);
  for (std::size_t j = 0; j < initial_components.size(); ++j)
    seeds_(initial_components[j], static_cast<Eigen::Index>(j)) = 1.0;
  // The region first: the integrator evaluates its field from the start.
  two_solutions_.clear();
  if (call_->hybrid) {
    start_sides(z0);
    crossings_.assign(system_.switching_count(), 0);
    crossing_times_.assign(system_.switching_count(), CrossingTimes{});
    redone_from_ = std::numeric_limits<double>::quiet_NaN();
    step_end_.t = std::numeric_limits<double>::quiet_NaN();
  }
  stepper_->start(t0, z0.data(), seeds_);
  forced_stop_.reset();
  bands_.assign(zones_.size(), -2);  // unknown: set from the state below
  last_abs_.assign(zones_.size(), std::numeric_limits<double>::infinity());
  approaching_.assign(zones_.size(), 1);
  update_bands(t0);
  ++statistics_.calls;
}

// The band of a zone is the innermost level l with |z_c| < v_l (-1 outside all levels). The
// step is capped at fraction * v_(l+1) / |dz_c/dt|: a step that crosses v_(l+1) then lands
// above v_(l+2) (fraction < 2/3), so no level is ever jumped, and the innermost band, the
// steep part itself, is crossed in several steps. Outside all levels the cap set where the
// component left them holds until it is back (by the swing's symmetry, its rate there is about
// the rate it left with).
void Flow::update_max_step(double t) {
  double hmax = options_.max_step > 0.0 ? options_.max_step : 0.0;
  if (!zones_.empty()) {
    const double* z = stepper_->state();
    call_->rhs(t, z, dz_scratch_.data());
    ++statistics_.rhs_evaluations;
    for (std::size_t i = 0; i < zones_.size(); ++i) {
      const double velocity = dz_scratch_[zones_[i].component];
      const double rate = std::abs(velocity);
      if (rate == 0.0) continue;
      const auto& levels = levels_[i];
      const int last = static_cast<int>(levels.size()) - 1;
      const bool outward = z[zones_[i].component] * velocity > 0.0;
      const int ahead = outward && outward_caps_looser(bands_[i], last)
                            ? bands_[i]
                            : std::min(bands_[i] + 1, last);
      const double cap = options_.steep_step_fraction * levels[ahead] / rate;
      hmax = hmax > 0.0 ? std::min(hmax, cap) : cap;
    }
  }
  stepper_->set_max_step(hmax);
  // The integrators apply a new maximum only when they next choose a step size; a step already
  // planned may exceed it. Shrink it with a stop time one cap ahead.
  forced_stop_.reset();
  if (hmax > 0.0)
    if (const auto planned = stepper_->planned_step(); planned && planned->h > hmax)
      forced_stop_ = planned->t + hmax;
}

// Within the levels but outside the innermost band, a component moving away from its zone has
// the band's outer level ahead of it, not the inner one: with a one-step method it is capped by
// that level, steps three times as long (the fast preset's anti-phase k-branch: 26 803 -> 24 724
// steps, 1.006e9 -> 0.953e9 instructions, the located points as close to the reference). Not
// lifted altogether: error control alone on the way out took 23 039 steps, but the results
// moved with the parameters by more noise, and the fast preset's BP curve in (k, c) from the
// anti-phase BP lost its way at the second point. CVODE's multistep methods keep the inner
// level: with the outer one, the default preset (Adams) took 1.7% more steps (145 521 ->
// 147 941), its order rebuilt after each jump in the step size.
bool Flow::outward_caps_looser(int band, int innermost) const {
  return options_.method == Method::ERK && band >= 0 && band < innermost;
}

// A state on a level counts as inside it.
int Flow::band_of(std::size_t zone, double value) const {
  int band = -1;
  const auto& levels = levels_[zone];
  for (int l = 0; l < static_cast<int>(levels.size()); ++l)
    if (std::abs(value) <= levels[l]) band = l;
  return band;
}

// The caps are set again when a band changes and, where the way out is capped more loosely, when
// a component turns back towards its zone within a band: seen one step late, from |z_c| before
// and after the step (the step that turned was capped by the band's outer level and chosen by
// error control near the turning point of z_c, where it moves slowly).
void Flow::update_bands(double t) {
  const double* z = stepper_->state();
  bool changed = false;
  for (std::size_t i = 0; i < zones_.size(); ++i) {
    const double value = std::abs(z[zones_[i].component]);
    const int band = band_of(i, value);
    const char approaching = value < last_abs_[i];
    const bool turned = approaching != approaching_[i];
    last_abs_[i] = value;
    approaching_[i] = approaching;
    if (band != bands_[i]) {
      if (bands_[i] != -2) ++statistics_.steep_roots;
      bands_[i] = band;
      changed = true;
    } else if (turned && outward_caps_looser(band, static_cast<int>(levels_[i].size()) - 1)) {
      changed = true;
    }
  }
  if (changed || bands_.empty()) update_max_step(t);
}

// The region of a hybrid system that z0 lies in: the sign of each switching function, or on a
// surface, the side the flow enters (saltation.hpp's side_entered, which refuses sliding and
// notes a start where two solutions begin).
void Flow::start_sides(const Eigen::VectorXd& z0) {
  const int m = system_.switching_count();
  const int n = system_.dimension();
  const double* p = call_->values.data();
  std::vector<double> g(m);
  system_.switching_functions(t_, z0.data(), p, g.data());
  call_->sides.assign(m, 1);
  for (int i = 0; i < m; ++i)
    if (g[i] < 0.0) call_->sides[i] = -1;
  Eigen::VectorXd f;  // the field at z0, where it lies on a surface
  for (int i = 0; i < m; ++i) {
    if (g[i] != 0.0) continue;
    if (f.size() == 0) {
      f.resize(n);
      system_.rhs(t_, z0.data(), p, f.data());
    }
    StartSide s = side_entered(*call_->hybrid, t_, z0, call_->values, call_->sides, i, f);
    call_->sides[i] = s.side;
    if (!s.two_solutions.empty())
      two_solutions_ += (two_solutions_.empty() ? "" : "; ") + s.two_solutions;
  }
}

// The crossings at this root, with their resets, and the sensitivity columns mapped across them
// (saltation.hpp). Which surfaces are crossed is decided here, not taken from the integrator's
// report alone: surface i is crossed where the flow leaves the side it is on, that is where h_i
// has the other sign, or where h_i is within the root finding's time tolerance of zero (CVODES:
// 100 uround max(|t|, |h|); here 1000 uround max(|t|, 1), against the rate h_z f- + h_t) and the
// flow moves across. Two identical pendula cross their surfaces together: the root finding stops
// at the first zero of all functions, the second one may then be a rounding error short of its
// zero, or exactly zero, which CVODES takes as inactive where it restarts, so that it would never
// report it; counted here, the two are one event (and their order is checked, saltation.hpp). A
// function reported again after it was counted so (it changes sign a rounding error later) is
// not crossed twice. A crossing against the surface's declared direction is no event: its side is
// only updated.
void Flow::cross_surfaces_here() {
  const int n = system_.dimension();
  const int m = system_.switching_count();
  const double* p = call_->values.data();
  const Eigen::VectorXd z = Eigen::Map<const Eigen::VectorXd>(stepper_->state(), n);
  std::vector<double> g(m);
  system_.switching_functions(t_, z.data(), p, g.data());
  Eigen::VectorXd f_minus(n);
  call_->hybrid->rhs_on_sides(t_, z.data(), p, call_->sides.data(), f_minus.data());
  Eigen::RowVectorXd h_z(n);
  const double window = 1e3 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_), 1.0);
  std::vector<int> surfaces;
  for (int i = 0; i < m; ++i) {
    const double h_t = call_->hybrid->switching_gradient(t_, z.data(), p, i, h_z.data());
    const double arrival = h_z.dot(f_minus) + h_t;
    const int sign = g[i] > 0.0 ? 1 : -1;
    const bool beyond = g[i] != 0.0 && sign != call_->sides[i];
    const bool at = std::abs(g[i]) <= window * std::abs(arrival) && arrival * call_->sides[i] < 0.0;
    if (!beyond && !at) continue;
    const int direction = call_->hybrid->crossing_direction(i);
    const int towards = beyond ? sign : -call_->sides[i];
    if (direction == 0 || direction == towards)
      surfaces.push_back(i);
    else
      call_->sides[i] = towards;
  }
  const bool derivatives = call_->columns > 0;
  HybridEvent event = cross_surfaces(*call_->hybrid, t_, z, call_->values, call_->sides, surfaces,
                                     call_->parameters, derivatives);
  call_->sides = std::move(event.sides);
  for (int i : surfaces) {
    ++crossings_[i];
    check_chattering(i);
  }
  Eigen::MatrixXd S(n, 0);
  if (derivatives) {
    stepper_->sensitivities(S);
    S = event.saltation * S;
    const auto np = static_cast<Eigen::Index>(call_->parameters.size());
    S.rightCols(np) += event.parameter_jump;
  }
  stepper_->restart_from(t_, event.state.data(), S);
}

// Crossings of one surface whose intervals shrink geometrically accumulate at a finite time (a
// Zeno point: a ball bouncing with restitution e under gravity returns after intervals 2 v e^k /
// g, which sum to 2 v / (g (1 - e))); past it the motion stays on the surface, which no region's
// field describes, and before it the flow would restart at each of infinitely many crossings.
// Refused as chattering where kChatterIntervals intervals in a row shrank by kChatterRatio or
// more (a factor 2.3 at least: an orbit's crossings repeat at a period, a transient's
// intervals do not shrink so steadily), or where an interval falls below the root finding's
// resolution (1e3 uround max(|t|, 1)), with the accumulation time extrapolated from the last
// ratio.
void Flow::check_chattering(int surface) {
  constexpr int kChatterIntervals = 8;
  constexpr double kChatterRatio = 0.9;
  CrossingTimes& c = crossing_times_[surface];
  const double interval = t_ - c.last;
  const double ratio = interval / c.interval;
  c.shrinking = ratio <= kChatterRatio ? c.shrinking + 1 : 0;
  c.last = t_;
  c.interval = interval;
  const double resolution =
      1e3 * std::numeric_limits<double>::epsilon() * std::max(std::abs(t_), 1.0);
  if (c.shrinking < kChatterIntervals && !(interval <= resolution)) return;
  const double accumulation = ratio < 1.0 ? t_ + interval * ratio / (1.0 - ratio) : t_;
  std::ostringstream msg;
  msg.precision(12);
  msg << "chattering: " << system_.switching_name(surface) << " crossed " << crossings_[surface]
      << " times, the intervals shrinking by a factor " << ratio << " each (the last " << interval
      << " at t = " << t_ << "): the crossings accumulate near t = " << accumulation
      << ", past which the flow stays on the surface, which it does not follow";
  throw NonsmoothFlowError(msg.str(), accumulation);
}

void Flow::on_switching() {
  // f jumps here: restart the integrator from the state at the surface (a hybrid system: from
  // the state after the crossings, with the sensitivities mapped across them).
  ++statistics_.switchings;
  collect_statistics();
  // A crossing changes the region (and a reset the state): the next step's start is computed anew.
  step_end_.t = std::numeric_limits<double>::quiet_NaN();
  if (call_->hybrid)
    cross_surfaces_here();
  else
    stepper_->restart(t_);
  forced_stop_.reset();
  update_max_step(t_);
}

// One internal step at a time: after each, the steep zones' bands are read off the state, and a
// changed band sets the step cap at once. `after_step(t_old, t_new)` may interpolate outputs in
// the step just taken before anything restarts the integrator; true stops there.
void Flow::integrate_to(double t_end, const std::function<bool(double, double)>& after_step) {
  // A failed call's work counts too (the caller collects only after a success).
  try {
    step_to(t_end, after_step);
  } catch (const IntegrationError&) {
    collect_statistics();
    throw;
  }
}

void Flow::step_to(double t_end, const std::function<bool(double, double)>& after_step) {
  // One step per call of the integrator, so its own step limit never triggers: count here, from
  // the start of the call or the last sample given (the samplers reset the count).
  for (steps_since_output_ = 0; t_ < t_end; ++steps_since_output_) {
    if (steps_since_output_ >= options_.max_steps) {
      std::ostringstream msg;
      msg << stepper_->name() << ": more than " << options_.max_steps
          << " steps before t = " << t_end << ", at t = " << t_;
      // Steps that shrink without end against a right-hand side that is not finite beyond them.
      if (!call_->nonfinite.empty()) msg << "; " << call_->nonfinite;
      throw IntegrationError(msg.str(), t_);
    }
    const bool forced = forced_stop_ && *forced_stop_ < t_end;
    stepper_->set_stop_time(forced ? *forced_stop_ : t_end);
    const double t_old = t_;
    const detail::StepOutcome outcome = stepper_->step(t_end, t_);
    if (call_->hybrid && outcome != detail::StepOutcome::Root && t_old != redone_from_) {
      if (const auto turn = hidden_excursion(t_old)) {
        // The step again, from its start, stopping at the excursion's turn: the root finding then
        // sees the surface's function change sign in it, and locates the first crossing.
        collect_statistics();
        Eigen::VectorXd z;
        Eigen::MatrixXd S;
        stepper_->interpolate(t_old, z, S);
        stepper_->restart_from(t_old, z.data(), S);
        t_ = t_old;
        redone_from_ = t_old;  // once: a turn that the retaken step still misses is a grazing
        step_end_.t = std::numeric_limits<double>::quiet_NaN();
        forced_stop_ = *turn;
        continue;
      }
    }
    if (after_step && after_step(t_old, t_)) return;
    if (outcome == detail::StepOutcome::Root) {
      on_switching();
      continue;
    }
    if (outcome == detail::StepOutcome::StopTime && forced)
      forced_stop_.reset();  // the shortened step is done
    if (!zones_.empty()) update_bands(t_);
  }
}

// A surface crossed twice inside one step (h leaves its side and comes back between the step's
// ends, as on an orbit just past a grazing) shows no sign change at the ends, where the root
// finding looks: seen here where h moves towards the surface at the step's start and away from it
// at its end. The cubic through h and its rate at the ends (h_z f + h_t, f the region's) says
// where it turns; where that turn comes within half of the ends' distance to the surface, the turn
// is found on the integrator's interpolant (bisection on the rate) and h evaluated there. The
// earliest turn beyond the surface, or nullopt.
// The step's start is the last one's end (kept in step_end_), unless the integrator restarted.
std::optional<double> Flow::hidden_excursion(double t_old) {
  const int n = system_.dimension();
  const int m = system_.switching_count();
  const double* p = call_->values.data();
  Eigen::RowVectorXd h_z(n);
  Eigen::VectorXd f(n);
  if (!(step_end_.t == t_old)) {
    step_end_.z.resize(n);
    stepper_->interpolate_state(t_old, step_end_.z);
    step_end_.g.resize(m);
    system_.switching_functions(t_old, step_end_.z.data(), p, step_end_.g.data());
    step_end_.f.resize(n);
    call_->rhs(t_old, step_end_.z.data(), step_end_.f.data());
  }
  const StepEnd start = std::move(step_end_);
  StepEnd& end = step_end_;
  end.t = t_;
  end.z = Eigen::Map<const Eigen::VectorXd>(stepper_->state(), n);
  end.g.resize(m);
  system_.switching_functions(t_, end.z.data(), p, end.g.data());
  end.f.resize(n);
  call_->rhs(t_, end.z.data(), end.f.data());
  const auto rate = [&](double t, const Eigen::VectorXd& z, const Eigen::VectorXd& f_z, int i) {
    const double h_t = call_->hybrid->switching_gradient(t, z.data(), p, i, h_z.data());
    return h_z.dot(f_z) + h_t;
  };
  const std::vector<double>& g_old = start.g;
  const std::vector<double>& g_new = end.g;
  std::vector<double> g(m);
  const double h = t_ - t_old;
  std::optional<double> first;
  Eigen::VectorXd z(n);
  for (int i = 0; i < m; ++i) {
    const double side = g_old[i] > 0.0 ? 1.0 : -1.0;
    if (g_old[i] == 0.0 || side * g_new[i] <= 0.0) continue;  // a sign change: the root finding's
    const double r0 = side * rate(t_old, start.z, start.f, i);
    const double r1 = side * rate(t_, end.z, end.f, i);
    if (!(r0 < 0.0 && r1 > 0.0)) continue;
    // The cubic in s = (t - t_old) / h through (side g, side g' h) at both ends; its turn is the
    // root of its derivative a s^2 + b s + c in (0, 1), where r0 < 0 < r1 puts exactly one.
    const double d0 = side * g_old[i], d1 = side * g_new[i];
    const double a = 3 * (2 * d0 - 2 * d1 + h * r0 + h * r1);
    const double b = 2 * (-3 * d0 + 3 * d1 - 2 * h * r0 - h * r1), c = h * r0;
    double s = 0.0, lo = 0.0, hi = 1.0;
    for (int k = 0; k < 60; ++k) {  // the derivative rises from c < 0 to h r1 > 0
      s = 0.5 * (lo + hi);
      ((a * s + b) * s + c < 0.0 ? lo : hi) = s;
    }
    const double s2 = s * s, s3 = s2 * s;
    const double cubic = (2 * s3 - 3 * s2 + 1) * d0 + (s3 - 2 * s2 + s) * h * r0 +
                         (3 * s2 - 2 * s3) * d1 + (s3 - s2) * h * r1;
    if (cubic > 0.5 * std::min(d0, d1)) continue;
    // On the interpolant: the turn where the rate changes sign, h there.
    double t_lo = t_old, t_hi = t_;
    for (int k = 0; k < 50 && t_hi - t_lo > 1e-15 * std::max(1.0, std::abs(t_)); ++k) {
      const double t_mid = 0.5 * (t_lo + t_hi);
      stepper_->interpolate_state(t_mid, z);
      call_->rhs(t_mid, z.data(), f.data());
      (side * rate(t_mid, z, f, i) < 0.0 ? t_lo : t_hi) = t_mid;
    }
    const double turn = 0.5 * (t_lo + t_hi);
    stepper_->interpolate_state(turn, z);
    system_.switching_functions(turn, z.data(), p, g.data());
    if (side * g[i] < 0.0 && (!first || turn < *first)) first = turn;
  }
  return first;
}

void Flow::collect_statistics() {
  stepper_->collect(statistics_);
}

Eigen::VectorXd Flow::advance(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                              double t1) {
  if (!(t1 >= t0)) throw std::invalid_argument("flow: end time before start time");
  start(z0, p, t0, {}, {});
  integrate_to(t1);
  collect_statistics();
  return Eigen::Map<const Eigen::VectorXd>(stepper_->state(), system_.dimension());
}

Eigen::VectorXd Flow::advance_observing_steps(
    const Eigen::VectorXd& z0, const ParameterValues& p, double t0, double t1,
    const std::function<void(double, double, const Eigen::VectorXd&)>& observer) {
  if (!(t1 >= t0)) throw std::invalid_argument("flow: end time before start time");
  start(z0, p, t0, {}, {});
  const int n = system_.dimension();
  Eigen::VectorXd z(n);
  integrate_to(t1, [&](double t_old, double t_new) {
    z = Eigen::Map<const Eigen::VectorXd>(stepper_->state(), n);
    observer(t_old, t_new, z);
    return false;
  });
  collect_statistics();
  return Eigen::Map<const Eigen::VectorXd>(stepper_->state(), n);
}

void Flow::sample(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                  std::span<const double> times,
                  const std::function<void(double, const Eigen::VectorXd&)>& observer) {
  sample_until(z0, p, t0, times, [&](double t, const Eigen::VectorXd& z) {
    observer(t, z);
    return false;
  });
}

bool Flow::sample_until(const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                        std::span<const double> times,
                        const std::function<bool(double, const Eigen::VectorXd&)>& done) {
  return sample_run(
      z0, p, t0, times, {}, {},
      [&](double t, const Eigen::VectorXd& z, const Eigen::MatrixXd&) { return done(t, z); });
}

FlowDerivatives Flow::advance_with_sensitivities(const Eigen::VectorXd& z0,
                                                 const ParameterValues& p, double t0, double t1,
                                                 bool state, std::span<const int> parameters) {
  return advance_with_sensitivities(z0, p, t0, t1, state, parameters, {}, {});
}

FlowDerivatives Flow::advance_with_sensitivities(
    const Eigen::VectorXd& z0, const ParameterValues& p, double t0, double t1, bool state,
    std::span<const int> parameters, std::span<const double> times,
    const std::function<void(double, const Eigen::VectorXd&)>& observer) {
  if (!(t1 >= t0)) throw std::invalid_argument("flow: end time before start time");
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!(times[i] >= (i == 0 ? t0 : times[i - 1]) && times[i] <= t1))
      throw std::invalid_argument("flow: sample times must be increasing and within [t0, t1]");
  const int n = system_.dimension();
  const int state_columns = state ? n : 0;
  const int columns = state_columns + static_cast<int>(parameters.size());
  if (columns == 0 && times.empty()) {
    FlowDerivatives r;
    r.state = advance(z0, p, t0, t1);
    return r;
  }
  std::vector<int> components(state_columns);
  for (int j = 0; j < state_columns; ++j) components[j] = j;
  start(z0, p, t0, components, parameters);
  std::size_t next = 0;
  for (; next < times.size() && times[next] <= t0; ++next) observer(times[next], z0);
  if (next < times.size()) {
    Eigen::VectorXd z;
    integrate_to(t1, [&](double, double t_new) {
      for (; next < times.size() && times[next] <= t_new; ++next) {
        stepper_->interpolate_state(times[next], z);
        observer(times[next], z);
        steps_since_output_ = 0;
      }
      return false;
    });
  } else {
    integrate_to(t1);
  }
  collect_statistics();

  FlowDerivatives r;
  r.state = Eigen::Map<const Eigen::VectorXd>(stepper_->state(), n);
  Eigen::MatrixXd S;
  stepper_->sensitivities(S);
  r.transition = S.leftCols(state_columns);
  r.parameter_sensitivities = S.rightCols(static_cast<Eigen::Index>(parameters.size()));
  return r;
}

void Flow::sample_with_sensitivities(
    const Eigen::VectorXd& z0, const ParameterValues& p, double t0, std::span<const double> times,
    std::span<const int> initial_components, std::span<const int> parameters,
    const std::function<void(double, const Eigen::VectorXd&, const Eigen::MatrixXd&)>& observer) {
  sample_run(z0, p, t0, times, initial_components, parameters,
             [&](double t, const Eigen::VectorXd& z, const Eigen::MatrixXd& S) {
               observer(t, z, S);
               return false;
             });
}

// Outputs at t0 itself (the seeds), then those inside each step, from the step's interpolant.
bool Flow::sample_run(
    const Eigen::VectorXd& z0, const ParameterValues& p, double t0, std::span<const double> times,
    std::span<const int> initial_components, std::span<const int> parameters,
    const std::function<bool(double, const Eigen::VectorXd&, const Eigen::MatrixXd&)>& observer) {
  if (times.empty()) return false;
  for (std::size_t i = 0; i < times.size(); ++i)
    if (!(times[i] >= (i == 0 ? t0 : times[i - 1])))
      throw std::invalid_argument("flow: sample times must be increasing and not before t0");
  start(z0, p, t0, initial_components, parameters);
  Eigen::VectorXd z = z0;
  Eigen::MatrixXd S = seeds_;
  std::size_t next = 0;
  while (next < times.size() && times[next] <= t0)
    if (observer(times[next++], z, S)) return true;
  bool stopped = false;
  integrate_to(times.back(), [&](double, double t_new) {
    while (!stopped && next < times.size() && times[next] <= t_new) {
      stepper_->interpolate(times[next], z, S);
      stopped = observer(times[next++], z, S);
      steps_since_output_ = 0;
    }
    return stopped;
  });
  collect_statistics();
  return stopped;
}

std::vector<double> sample_times(double t_end, double dt) {
  const long count = static_cast<long>(std::floor(t_end / dt + 1e-9));
  std::vector<double> times;
  times.reserve(count + 2);
  for (long i = 0; i <= count; ++i) times.push_back(i * dt);
  if (t_end - times.back() > 1e-12) times.push_back(t_end);
  return times;
}

}  // namespace sympathy
