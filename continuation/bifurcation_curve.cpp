#include "sympathy/continuation/bifurcation_curve.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <utility>

#include "curve_system.hpp"
#include "sympathy/continuation/crossing_locator.hpp"
#include "sympathy/continuation/driver.hpp"
#include "sympathy/continuation/grazing.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

using detail::CriticalBlock;
using detail::CurveSystem;

OptionCheck CurveOptions::validate() const {
  if (!(std::isfinite(first_lower) && std::isfinite(first_upper) && first_lower < first_upper))
    return OptionProblem{"first window", "finite bounds, the lower below the upper"};
  if (!(std::isfinite(second_lower) && std::isfinite(second_upper) && second_lower < second_upper))
    return OptionProblem{"second window", "finite bounds, the lower below the upper"};
  for (const UserValue& v : user_values)
    if (!(v.quantity == UserValue::Quantity::Period && v.value > 0.0) &&
        !(v.quantity == UserValue::Quantity::Parameter && v.parameter >= 0 &&
          std::isfinite(v.value)))
      return OptionProblem{"user_values",
                           "positive periods or values of a parameter (a curve's points carry no "
                           "others)"};
  if (auto wrong = driver::step_options(*this).validate()) return wrong;  // the step fields
  if (max_iterations < 1) return OptionProblem{"max_iterations", "a positive integer"};
  if (!positive(tolerance)) return OptionProblem{"tolerance", "a positive number"};
  if (!positive(location_tolerance))
    return OptionProblem{"location_tolerance", "a positive number"};
  if (!(std::isfinite(end_radius) && end_radius >= 0.0 && std::isfinite(end_first) &&
        std::isfinite(end_second)))
    return OptionProblem{"end_radius", "a number >= 0 (0: none) and a finite end point"};
  return nested("orbit.", orbit.validate());
}

namespace {

// Scalar functions along a curve whose sign changes mark codimension-two points.
struct Watch {
  std::string type, description;
  // The function's value at a point; NaN where it does not apply.
  std::function<double(const CurvePoint&)> value;
  // A multiplier followed from probe to probe (another one crossing the unit circle).
  std::shared_ptr<std::complex<double>> tracked = nullptr;
};

// The curve's first (k = 0) or second parameter at p.
double parameter_value(int k, const CurvePoint& p) {
  return k == 0 ? p.first : p.second;
}

// How far a point is from (first, second), in the curve's scaled norm (each parameter by its
// window).
double window_distance(const CurveSystem& system, const CurvePoint& a,
                       const std::pair<double, double>& b) {
  const double d0 = (a.first - b.first) * system.weight(system.first_index());
  const double d1 = (a.second - b.second) * system.weight(system.second_index());
  return std::hypot(d0, d1);
}

const char* kind_of_crossing(std::complex<double> mu, SymmetryKind symmetry) {
  if (std::abs(mu.imag()) > 1e-6) return "NS";
  if (mu.real() < 0.0) return "PD";
  return symmetry == SymmetryKind::Breaking ? "BP" : "LP";
}

// A point of the curve as the driver follows it: the point with what the next step starts from
// (its chord Jacobian and the borders under which it was assembled), so that a rejected step
// leaves the system as it was.
struct CurveNode : CurvePoint {
  Eigen::MatrixXd jacobian;
  std::optional<BorderedSingularity> borders;
};

// One half of a curve, as the driver's problem (driver.hpp).
class CurveContinuation {
 public:
  using Point = CurveNode;
  using Event = CurveEvent;

  // `origin`: the event's (first, second) parameters, where the curve was started; `start`: the
  // curve's first point, which a closed curve comes back to.
  CurveContinuation(CurveSystem& system, const BifurcationCurve& curve, const CurveOptions& options,
                    std::pair<double, double> origin, const CurvePoint& start)
      : system_(system), curve_(curve), options_(options), origin_(origin), start_(start) {}

  driver::Attempt<Point> step(const Point*, const Point& a, double ds);
  double turn_cosine(const Point& a, const Point& b) const {
    return system_.dot(b.tangent, a.tangent);
  }
  bool outside(const Point& b) const { return !inside(b.unknowns); }
  std::string edge_message(const Point& b) const {
    return "reached the edge of the window at " + curve_.first_name + " = " +
           format_number(b.first) + ", " + curve_.second_name + " = " + format_number(b.second);
  }
  std::optional<Point> onto_edge(const Point& a, const Point& b);
  driver::Found<Event> detect(const Point*, const Point& a, const Point& b);
  std::optional<driver::Ending> ends(const Point& a, const Point& b, std::vector<Event>&);
  void accept(Point&) {
    if (!crossings_b_.empty()) crossings_ = std::move(crossings_b_);
  }
  double parameter(const Point& p) const { return p.first; }

 private:
  bool inside(const Eigen::VectorXd& u) const;
  // The node at a converged correction: the borders moved to its null vectors first, so that
  // its Jacobian (the chord of the next step) has g's row under the borders that step will use.
  std::optional<Point> complete(CurveSystem::Correction& r, const Point& a, std::string& why);
  // The curve's point at arclength s from a along a's tangent, from a's chord Jacobian (in the
  // section and under the borders set now): what a step and every location probe correct.
  CurveSystem::Correction along(const Point& a, double s);
  std::vector<Watch> watches() const;
  CurveEvent locate(const Watch& w, const Point& from, const Point& to, double f0, double f1);
  CurveEvent locate_turn(int k, const Point& from, const Point& to, double t0);
  // A hybrid orbit's crossings per period at the curve's unknowns u (grazing.hpp), and the
  // step's arclength and note of where they change between a and b.
  std::vector<int> crossings_of(const Eigen::VectorXd& u) const;
  std::optional<driver::Ending> grazing(const Point& a, const Point& b, std::vector<Event>& events);

  CurveSystem& system_;
  const BifurcationCurve& curve_;
  const CurveOptions& options_;
  std::pair<double, double> origin_;
  const CurvePoint& start_;
  double farthest_ = 0.0;               // from the start, in the scaled norm
  std::optional<std::string> stop_at_;  // a stop passed in the step detect saw last: its note
  // A hybrid system's: the last accepted point's crossings per period, and the step's end's,
  // which accept() keeps (empty for a smooth system).
  std::vector<int> crossings_, crossings_b_;
};

bool CurveContinuation::inside(const Eigen::VectorXd& u) const {
  const double p1 = u[system_.first_index()], p2 = u[system_.second_index()];
  return p1 >= options_.first_lower && p1 <= options_.first_upper && p2 >= options_.second_lower &&
         p2 <= options_.second_upper;
}

std::optional<CurveNode> CurveContinuation::complete(CurveSystem::Correction& r, const Point& a,
                                                     std::string& why) {
  system_.set_borders(*a.borders);
  system_.update_borders(r.evaluation);
  system_.assemble(r.u, r.evaluation);
  const auto jacobian = system_.jacobian(r.u, r.evaluation);
  if (!jacobian) {
    why = "a difference of the Jacobian could not be integrated";
    return std::nullopt;
  }
  const Eigen::VectorXd t = system_.tangent(*jacobian, a.tangent);
  CurveNode n;
  static_cast<CurvePoint&>(n) = system_.point(r.u, r.evaluation, *jacobian, t);
  n.iterations = r.iterations;
  n.jacobian = *jacobian;
  n.borders = system_.borders();
  return n;
}

CurveSystem::Correction CurveContinuation::along(const Point& a, double s) {
  CurveSystem::Condition c;
  c.tangent = a.tangent;
  c.from = a.unknowns;
  c.step = s;
  return system_.correct(a.unknowns + s * a.tangent, c, a.jacobian);
}

driver::Attempt<CurveNode> CurveContinuation::step(const Point*, const Point& a, double ds) {
  system_.set_section(a.unknowns);
  system_.set_borders(*a.borders);
  driver::Attempt<Point> attempt;
  auto r = along(a, ds);
  if (!r.converged) {
    attempt.why = r.reason;
    return attempt;
  }
  attempt.point = complete(r, a, attempt.why);
  if (attempt.point) attempt.point->step = ds;
  return attempt;
}

std::optional<CurveNode> CurveContinuation::onto_edge(const Point& a, const Point& b) {
  // The parameter that left the window, held at its bound.
  const Eigen::VectorXd& u = b.unknowns;
  const int i1 = system_.first_index(), i2 = system_.second_index();
  CurveSystem::Condition e;
  if (u[i1] < options_.first_lower || u[i1] > options_.first_upper) {
    e.index = i1;
    e.value = u[i1] < options_.first_lower ? options_.first_lower : options_.first_upper;
  } else {
    e.index = i2;
    e.value = u[i2] < options_.second_lower ? options_.second_lower : options_.second_upper;
  }
  system_.set_section(a.unknowns);
  system_.set_borders(*a.borders);
  const double t = (e.value - a.unknowns[e.index]) / (u[e.index] - a.unknowns[e.index]);
  auto r = system_.correct(a.unknowns + t * (u - a.unknowns), e, a.jacobian);
  if (!r.converged) return std::nullopt;
  std::string why;
  auto n = complete(r, a, why);
  if (n) n->step = system_.norm(n->unknowns - a.unknowns);
  return n;
}

std::vector<int> CurveContinuation::crossings_of(const Eigen::VectorXd& u) const {
  PeriodicOrbit orbit;
  orbit.state0 = system_.state(u);
  orbit.period = u[system_.first_index() - 1];
  orbit.parameters = system_.values(u);
  return crossings_per_period(system_.system(), system_.options().orbit.shooting.flow, orbit);
}

// A curve of hybrid orbits ends where its orbits' crossings per period change, as a branch does
// (grazing.hpp): bisection in the arclength from a, each probe corrected onto the curve, to the
// location tolerance (scaled arclength); b not kept, the step's events located beyond the
// bracket's near end dropped (their orbits lie past the grazing).
std::optional<driver::Ending> CurveContinuation::grazing(const Point& a, const Point& b,
                                                         std::vector<Event>& events) {
  const auto where = [&](const Eigen::VectorXd& u) {
    return curve_.first_name + " = " + format_number(u[system_.first_index()]) + ", " +
           curve_.second_name + " = " + format_number(u[system_.second_index()]);
  };
  try {
    if (crossings_.empty()) crossings_ = crossings_of(a.unknowns);
    crossings_b_ = crossings_of(b.unknowns);
  } catch (const IntegrationError& e) {
    return driver::Ending{driver::Stop::Nonsmooth,
                          "the orbit at " + where(b.unknowns) + " is not smooth: " + e.what(),
                          false};
  }
  if (crossings_b_ == crossings_) return std::nullopt;
  system_.set_section(a.unknowns);
  system_.set_borders(*b.borders);
  // The probes' unknowns by their arclength (only what the crossings and the note need: no
  // multipliers of a probe).
  std::map<double, Eigen::VectorXd> probed{{0.0, a.unknowns}, {b.step, b.unknowns}};
  const CrossingBracket bracket = bisect_crossing_change(
      b.step, crossings_,
      [&](double s, std::string& why) -> std::optional<std::vector<int>> {
        auto r = along(a, s);
        if (!r.converged) {
          why = r.reason;
          return std::nullopt;
        }
        probed[s] = r.u;
        try {
          return crossings_of(r.u);
        } catch (const IntegrationError& e) {
          why = e.what();
          return std::nullopt;
        }
      },
      [&](double near, double far) { return far - near <= options_.location_tolerance; });
  const Eigen::VectorXd &near = probed.at(bracket.near), &far = probed.at(bracket.far);
  std::string note =
      "grazing near " + where(far) + " (probes " + format_number(system_.norm(far - near)) +
      " apart, scaled): " + describe_crossing_change(system_.system(), crossings_, crossings_b_) +
      "; the orbits' flow has no derivative there, so the curve ends";
  if (!bracket.failed.empty()) note += "; a probe failed: " + bracket.failed;
  std::erase_if(events, [&](const CurveEvent& e) {
    return system_.norm(e.at.unknowns - a.unknowns) > bracket.near;
  });
  return driver::Ending{driver::Stop::Nonsmooth, note, false};
}

std::optional<driver::Ending> CurveContinuation::ends(const Point& a, const Point& b,
                                                      std::vector<Event>& events) {
  // A period the curve was asked to stop at, passed in this step: b not kept (the curve's orbit
  // there is the event's).
  if (stop_at_) {
    const std::string note = *stop_at_;
    stop_at_.reset();
    return driver::Ending{driver::Stop::UserValue, "reached the value asked for: " + note, false};
  }
  if (system_.system().switching_count() > 0)
    if (auto g = grazing(a, b, events)) return g;
  // Near the point the curve was born from, where it degenerates (CurveOptions::end_radius): b
  // kept, the last point before it.
  if (options_.end_radius > 0.0 &&
      window_distance(system_, b, {options_.end_first, options_.end_second}) <= options_.end_radius)
    return driver::Ending{driver::Stop::HopfPoint,
                          "ended near " + options_.end_name + " at " + curve_.first_name + " = " +
                              format_number(options_.end_first) + ", " + curve_.second_name +
                              " = " + format_number(options_.end_second) +
                              ", where its orbits shrink into the equilibrium",
                          true};
  // Back at the start: the curve went away from it and the last step passed through it
  // (driver::on_chord). A point merely near the start in the scaled norm is not enough: two NS
  // points 6 N/m apart on a 1-100 N/m window are 0.06 apart, about one step.
  farthest_ = std::max(farthest_, system_.norm(b.unknowns - start_.unknowns));
  const auto dot = [&](const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    return system_.dot(u, v);
  };
  if (farthest_ > 4.0 * options_.max_step &&
      driver::on_chord(start_.unknowns, a.unknowns, b.unknowns, dot))
    return driver::Ending{driver::Stop::Closed, "closed: back at the start", true};
  return std::nullopt;
}

std::vector<Watch> CurveContinuation::watches() const {
  std::vector<Watch> w;
  if (curve_.kind == BifurcationType::NeimarkSacker) {
    // kappa = Re of the pair's mean: cos(theta) on the circle, (mu + 1/mu) / 2 on a neutral
    // saddle; the strong resonances at theta = 0, pi, 2 pi / 3, pi / 2.
    const auto kappa = [](const CurvePoint& p) {
      return 0.5 * (p.critical[0] + p.critical[1]).real();
    };
    w.push_back({"R1", "1:1 resonance: the pair meets at +1",
                 [kappa](const CurvePoint& p) { return kappa(p) - 1.0; }});
    w.push_back({"R2", "1:2 resonance: the pair meets at -1",
                 [kappa](const CurvePoint& p) { return kappa(p) + 1.0; }});
    w.push_back(
        {"R3", "1:3 resonance: the pair at exp(+-2 pi i / 3)", [kappa](const CurvePoint& p) {
           return p.neutral_saddle ? std::nan("") : kappa(p) + 0.5;
         }});
    w.push_back({"R4", "1:4 resonance: the pair at +-i", [kappa](const CurvePoint& p) {
                   return p.neutral_saddle ? std::nan("") : kappa(p);
                 }});
  }
  return w;
}

CurveEvent CurveContinuation::locate(const Watch& w, const Point& from, const Point& to, double f0,
                                     double f1) {
  // The one locator (crossing_locator.hpp) in the arclength from `from` along its tangent, each
  // probe a point corrected onto the curve under the arclength condition there, narrowed in that
  // arclength (scaled): a curve may run along either parameter.
  CurveEvent e;
  e.type = w.type;
  e.description = w.description;
  using Probe = std::pair<double, CurvePoint>;  // its arclength, and the point
  using Tag = int;
  const auto probe = [&](double s, std::string& why) -> std::optional<Probe> {
    auto r = along(from, s);
    if (!r.converged) {
      why = r.reason;
      return std::nullopt;
    }
    return Probe{s, system_.point(r.u, r.evaluation, from.jacobian, from.tangent)};
  };
  const auto test = [&](const Probe& p, double, const driver::End<Tag>&, const driver::End<Tag>&) {
    return driver::Sample<Tag>{w.value(p.second), 0};
  };
  driver::LocatorOptions o;
  o.tolerance = options_.location_tolerance;
  o.floor = 1.0;  // an absolute tolerance in the arclength
  o.max_probes = 40;
  system_.set_section(from.unknowns);
  system_.set_borders(*to.borders);
  auto c = driver::locate_crossing(
      Probe{0.0, from}, driver::Sample<Tag>{f0, 0}, Probe{to.step, to}, driver::Sample<Tag>{f1, 0},
      to.step, test, probe, [](const Probe& p) { return p.first; }, o);
  e.located = c.located();
  // At least one probe converged (a failed one is the last).
  const bool have = c.probes > (c.outcome == driver::LocatorOutcome::ProbeFailed ? 1 : 0);
  if (c.outcome == driver::LocatorOutcome::ProbeFailed) e.note = "a probe failed: " + c.why;
  const CurvePoint& best = c.point.second;
  if (!have) {
    // No probe converged: where the watched function's chord between the points is zero.
    const double t = f0 / (f0 - f1);
    e.at = t < 0.5 ? static_cast<const CurvePoint&>(from) : to;
    e.first = from.first + t * (to.first - from.first);
    e.second = from.second + t * (to.second - from.second);
    e.uncertainty = std::abs(to.first - from.first);
  } else {
    e.at = best;
    e.first = best.first;
    e.second = best.second;
    // The bracket's width in the first parameter, and the point's own uncertainty.
    const double speed = std::abs(from.tangent[system_.first_index()]);
    e.uncertainty = c.bracket * speed + best.uncertainty;
  }
  if (w.type == "other") {
    // Name it by the crossing multiplier (at the point after it, where no probe converged).
    const CurvePoint& named = have ? best : static_cast<const CurvePoint&>(to);
    const auto rest = system_.others(named);
    std::complex<double> nearest = rest.empty() ? 0.0 : rest.front();
    for (const auto& mu : rest)
      if (std::abs(std::log(std::abs(mu))) < std::abs(std::log(std::abs(nearest)))) nearest = mu;
    if (w.tracked) nearest = *w.tracked;  // the multiplier followed, where the last probe had it
    // Its label: that of the point's other multiplier nearest to it (the tracked value is the
    // last probe's; the point named may be another probe's).
    SymmetryKind symmetry = SymmetryKind::Unlabelled;
    double distance = INFINITY;
    for (int i : system_.other_indices(named)) {
      const Multiplier& m = named.floquet.multipliers[i];
      if (std::abs(m.value - nearest) < distance) {
        distance = std::abs(m.value - nearest);
        symmetry = m.symmetry;
      }
    }
    // Where the curve is a fold or a branch point, its own critical multiplier sits at +1 beside
    // the crossing one, and which of the two the curve took as its own is rounding (the (k, c)
    // map's in-phase fold curve meets a BP curve at (53.726, 0.426) with 1 + 1.3e-10, breaking
    // the symmetry, taken as the fold's, and 1 - 1.5e-10, keeping it, as the other): the other is
    // the one whose label is not the curve's own kind's, where the two differ.
    if (curve_.kind == BifurcationType::Fold || curve_.kind == BifurcationType::BranchPoint) {
      const SymmetryKind own = curve_.kind == BifurcationType::BranchPoint ? SymmetryKind::Breaking
                                                                           : SymmetryKind::Keeping;
      for (int i = 0; i < static_cast<int>(named.floquet.multipliers.size()); ++i) {
        const Multiplier& m = named.floquet.multipliers[i];
        if (i != named.floquet.trivial && std::abs(m.value - nearest) <= 1e-6 &&
            m.symmetry != SymmetryKind::Unlabelled && m.symmetry != own)
          symmetry = m.symmetry;
      }
    }
    const std::string other = kind_of_crossing(nearest, symmetry);
    e.crossing_symmetry = symmetry;
    e.type = to_string(curve_.kind) + "-" + other;
    e.description = "the " + to_string(curve_.kind) + " curve meets an " + other +
                    " curve: a multiplier " + format_number(nearest.real()) +
                    (nearest.imag() >= 0 ? "+" : "") + format_number(nearest.imag()) +
                    "i crosses the unit circle";
  }
  if (!e.located && e.note.empty()) e.note = "not narrowed to the location tolerance";
  return e;
}

CurveEvent CurveContinuation::locate_turn(int k, const Point& from, const Point& to, double t0) {
  const double step = to.step;
  // Near a turn the curve's value of parameter k is a parabola in the arclength s from `from`
  // (along its tangent, each probe corrected onto the curve under the arclength condition), its
  // vertex the turn: parabolic interpolation through the three latest samples converges
  // superlinearly, and the value at the vertex is fixed to the square of the error in s.
  const std::string name = k == 0 ? curve_.first_name : curve_.second_name;
  const auto value = [k](const CurvePoint& p) { return parameter_value(k, p); };
  CurveEvent e;
  e.type = "turn in " + name;
  e.description = "the curve turns back in " + name;
  e.after_point = from.index;
  std::vector<std::pair<double, CurvePoint>> samples{{0.0, from}, {step, to}};
  system_.set_section(from.unknowns);
  system_.set_borders(*to.borders);
  // The vertex in the arclength is fixed only to about the square root of the points' noise over
  // the curvature (1e-9 noise: some 3e-5), however many probes: narrowed to 1e-7 at most, and
  // the uncertainty says how far it got (the turned parameter's value is fixed far better).
  const double tolerance = std::max(options_.location_tolerance, 1e-7);
  double t = t0, previous = step;
  bool have = false;
  for (int probe = 0; probe < 12; ++probe) {
    t = std::clamp(t, 0.0, step);
    const auto r = along(from, t);
    if (!r.converged) {
      e.note = "a probe failed: " + r.reason;
      break;
    }
    samples.push_back({t, system_.point(r.u, r.evaluation, from.jacobian, from.tangent)});
    have = true;
    if (std::abs(t - previous) <= tolerance) break;
    previous = t;
    // The three samples nearest to the latest; the vertex of the parabola through them.
    std::sort(samples.begin(), samples.end(), [t](const auto& a, const auto& b) {
      return std::abs(a.first - t) < std::abs(b.first - t);
    });
    samples.resize(3);
    const double s0 = samples[0].first, s1 = samples[1].first, s2 = samples[2].first;
    const double v0 = value(samples[0].second), v1 = value(samples[1].second),
                 v2 = value(samples[2].second);
    const double d01 = (v1 - v0) / (s1 - s0), d12 = (v2 - v1) / (s2 - s1);
    const double curvature = (d12 - d01) / (s2 - s0);
    if (!(std::abs(curvature) > 0.0) || !std::isfinite(curvature)) break;
    t = 0.5 * (s0 + s1) - d01 / (2.0 * curvature);
  }
  const auto& best =
      std::min_element(samples.begin(), samples.end(), [t](const auto& a, const auto& b) {
        return std::abs(a.first - t) < std::abs(b.first - t);
      })->second;
  e.at = best;
  e.first = best.first;
  e.second = best.second;
  e.located = have && std::abs(t - previous) <= tolerance;
  // In the first parameter: its speed along the curve times the last correction of s (at a
  // turn in the first parameter itself, far less: the square of it).
  e.uncertainty =
      std::abs(t - previous) * std::abs(from.tangent[system_.first_index()]) + best.uncertainty;
  if (!e.located && e.note.empty()) e.note = "not narrowed to the location tolerance";
  return e;
}

driver::Found<CurveEvent> CurveContinuation::detect(const Point*, const Point& from,
                                                    const Point& to) {
  driver::Found<CurveEvent> found;
  std::vector<CurveEvent>& events = found.events;
  // AUTO's UZ and UZSTOP on the period, on the locator of the codimension-two points.
  stop_at_.reset();
  for (const UserValue& v : options_.user_values) {
    // The period, or the curve's first or second parameter (continue_curve checked it is one).
    const bool first = v.parameter == curve_.first;
    const auto quantity = [&v, first](const CurvePoint& p) {
      if (v.quantity == UserValue::Quantity::Period) return p.period;
      return first ? p.first : p.second;
    };
    const double f0 = quantity(from) - v.value, f1 = quantity(to) - v.value;
    if (f0 == 0.0 || (f1 != 0.0 && (f0 < 0.0) == (f1 < 0.0))) continue;
    const std::string note =
        (v.stop ? "stop at " : "user value ") + v.name + " = " + format_number(v.value);
    const double value = v.value;
    CurveEvent e =
        locate({"UZ", note, [value, quantity](const CurvePoint& p) { return quantity(p) - value; }},
               from, to, f0, f1);
    e.after_point = from.index;
    if (v.stop && !stop_at_) stop_at_ = note;
    events.push_back(std::move(e));
  }
  if (!options_.detect) {
    for (const auto& e : events) found.unlocated |= !e.located;
    return found;
  }
  for (const auto& w : watches()) {
    const double f0 = w.value(from), f1 = w.value(to);
    if (!(std::isfinite(f0) && std::isfinite(f1)) || (f0 < 0.0) == (f1 < 0.0)) continue;
    if (f0 == 0.0) continue;  // found at the previous step
    CurveEvent e = locate(w, from, to, f0, f1);
    e.after_point = from.index;
    events.push_back(e);
  }
  // Another multiplier through the unit circle: the number outside it changed. Each multiplier
  // of `to` is paired with the nearest of `from`'s; one whose modulus crossed 1 is followed, by
  // continuity from probe to probe (the one nearest to where it was), and its log-modulus
  // located. Watching whichever multiplier is nearest to the circle instead would see sign
  // changes where that role passes from one multiplier to another.
  const auto outside = [](const std::vector<std::complex<double>>& mu) {
    return std::count_if(mu.begin(), mu.end(), [](auto m) { return std::abs(m) > 1.0; });
  };
  const auto before = system_.others(from), after = system_.others(to);
  if (outside(before) != outside(after)) {
    for (const auto& m1 : after) {
      const auto m0 = *std::min_element(before.begin(), before.end(), [&](auto a, auto b) {
        return std::abs(a - m1) < std::abs(b - m1);
      });
      if ((std::abs(m0) > 1.0) == (std::abs(m1) > 1.0)) continue;
      if (m1.imag() < 0.0) continue;  // a complex pair once, by its upper member
      auto tracked = std::make_shared<std::complex<double>>(m0);
      Watch w{"other", "",
              [this, tracked](const CurvePoint& p) {
                const auto rest = system_.others(p);
                if (rest.empty()) return std::nan("");
                const auto m = *std::min_element(rest.begin(), rest.end(), [&](auto a, auto b) {
                  return std::abs(a - *tracked) < std::abs(b - *tracked);
                });
                *tracked = m;
                return std::log(std::abs(m));
              },
              tracked};
      const double f0 = std::log(std::abs(m0)), f1 = std::log(std::abs(m1));
      CurveEvent e = locate(w, from, to, f0, f1);
      // A crossing at the curve's own start is the start's degeneracy, which its origin names:
      // a BP curve born at a 1:1 resonance has the pair's other multiplier at +1 there too, and
      // it leaves +1 in the first step (located 7e-9 N/m from the R1 point it was born at on the
      // row setup's (k, c) map). Within 1e-6 of the window from the event the curve was started
      // at, in the two parameters: not from the first point, which a curve that leaves its origin
      // as a square root puts far from it (the resonance form's BP curve omega = -mu^2 from an
      // R1 located at omega = -2.3e-11 starts at mu = 4.8e-6; its meeting at the R1 point, at
      // mu = 3e-11, was taken for a meeting on the curve).
      if (from.index == 0 && e.located && window_distance(system_, e.at, origin_) <= 1e-6) continue;
      e.after_point = from.index;
      events.push_back(e);
    }
  }
  // The curve turning back in a parameter: where the tangent's component changes sign, located
  // from there (locate_turn).
  const int indices[2] = {system_.first_index(), system_.second_index()};
  for (int k = 0; k < 2; ++k) {
    // In the scaled norm; a curve that runs along the other parameter's direction has this
    // component at the noise level, and its sign means nothing.
    const double a = from.tangent[indices[k]] * system_.weight(indices[k]);
    const double b = to.tangent[indices[k]] * system_.weight(indices[k]);
    if ((a < 0.0) == (b < 0.0) || std::max(std::abs(a), std::abs(b)) < 1e-3) continue;
    CurveEvent turn = locate_turn(k, from, to, to.step * a / (a - b));
    // A turn is an extremum of the parameter: its value beyond both points' (or at the curve's
    // start, where the component is below the gate: a start at a vertex). Else the tangents' signs
    // disagreed by noise: a BP curve in (k, c) that runs almost along c at the fast preset, its k
    // component 2e-3 of the scaled tangent, "turned" ten times in 30 points whose k fell
    // steadily. (A turn whose excess over an end is below the points' noise is lost with them.)
    const double v = parameter_value(k, turn.at), v0 = parameter_value(k, from),
                 v1 = parameter_value(k, to);
    const bool at_start = from.index == 0 && turn.located && std::abs(a) < 1e-3;
    if (!((v - v0) * (v - v1) > 0.0) && !at_start) continue;
    events.push_back(std::move(turn));
  }
  for (const auto& e : events) found.unlocated |= !e.located;
  return found;
}

}  // namespace

BifurcationCurve continue_curve(const OdeSystem& system, const Branch& branch,
                                const Bifurcation& event, int second, const CurveOptions& options,
                                const CurveCallbacks& callbacks) {
  const Stopwatch clock;
  if (const auto problem = options.validate())
    throw std::invalid_argument("curve options: " + problem->message());
  if (!system.autonomous())
    throw std::invalid_argument("curve: for autonomous systems (not yet periodically forced ones)");
  const auto names = system.parameter_names();
  if (second < 0 || second >= static_cast<int>(names.size()))
    throw std::invalid_argument("curve: the second parameter is not a parameter of the system");
  if (second == branch.parameter)
    throw std::invalid_argument("curve: the second parameter (" + names[second] +
                                ") is the branch's own; expected another one");
  for (const UserValue& v : options.user_values)
    if (v.quantity == UserValue::Quantity::Parameter && v.parameter != branch.parameter &&
        v.parameter != second)
      throw std::invalid_argument("curve: a user value of a parameter the curve does not vary");
  if (!event.located())
    throw std::invalid_argument("curve: the " + to_string(event.type) + " at " +
                                branch.parameter_name + " = " + format_number(event.parameter) +
                                " is not located");
  if (event.trust == EventTrust::NoCrossingMultiplier)
    throw std::invalid_argument("curve: the " + to_string(event.type) + " at " +
                                branch.parameter_name + " = " + format_number(event.parameter) +
                                " is where the branch turned back without a multiplier at +1 "
                                "(an orbit shrinking into an equilibrium), not a fold of cycles");
  const InvariantSubspace subspace =
      branch.points.empty() ? InvariantSubspace() : branch.points.front().orbit.subspace;
  CriticalBlock block = CriticalBlock::Inside;
  switch (event.type) {
    case BifurcationType::Fold:
      block = CriticalBlock::Shooting;
      break;
    case BifurcationType::BranchPoint:
      if (subspace.is_whole_space() || event.symmetry != SymmetryKind::Breaking)
        throw std::invalid_argument(
            "curve: a BP curve follows a symmetry-breaking branch point, and this BP breaks no "
            "declared symmetry (the branch's start must declare the subspace it leaves)");
      block = CriticalBlock::Across;
      break;
    default:
      block =
          event.symmetry == SymmetryKind::Breaking ? CriticalBlock::Across : CriticalBlock::Inside;
  }
  const ParameterValues base =
      system.with_parameter(branch.start_values, branch.parameter, event.parameter);
  const double p2 = system.parameter(base, second);
  if (event.parameter < options.first_lower || event.parameter > options.first_upper ||
      p2 < options.second_lower || p2 > options.second_upper)
    throw std::invalid_argument("curve: the window does not contain the event (" +
                                branch.parameter_name + " = " + format_number(event.parameter) +
                                ", " + names[second] + " = " + format_number(p2) + ")");

  BifurcationCurve curve;
  curve.kind = event.type;
  curve.first = branch.parameter;
  curve.second = second;
  curve.first_name = branch.parameter_name;
  curve.second_name = names[second];
  curve.state_names = system.state_names();
  curve.subspace = subspace.description();
  curve.symmetry = event.symmetry;
  curve.options = options;
  curve.start_values = base;
  curve.origin = to_string(event.type) + " at " + branch.parameter_name + " = " +
                 format_number(event.parameter);

  CurveSystem s(system, event.type, subspace, block, branch.parameter, second, base, options);
  s.wind_as(event.state0, event.period, base);
  Eigen::VectorXd u = s.unknowns_of(event.state0, event.period, event.parameter, p2);
  s.set_scales(u);
  s.set_section(u);
  const auto finish = [&](StopReason stop, std::string reason) {
    curve.stop = stop;
    curve.stop_reason = std::move(reason);
    curve.flow = s.statistics();
    curve.evaluations = s.evaluations();
    curve.seconds = clock.seconds();
    return curve;
  };
  // The event onto the augmented system at its own second parameter: only the first moves.
  auto e = s.evaluate(u);
  if (!e.ok) return finish(StopReason::StartFailed, "the event cannot be integrated: " + e.failure);
  s.measure_noise(u, e);
  curve.noise = s.noise();
  auto j = s.jacobian(u, e);
  if (!j) return finish(StopReason::StartFailed, "the event's Jacobian cannot be integrated");
  CurveSystem::Condition hold;
  hold.index = s.second_index();
  hold.value = p2;
  auto r = s.correct(u, hold, *j);
  if (!r.converged)
    return finish(StopReason::StartFailed, "the event is not corrected onto the " +
                                               to_string(event.type) + " curve: " + r.reason);
  s.update_borders(r.evaluation);
  s.assemble(r.u, r.evaluation);
  j = s.jacobian(r.u, r.evaluation);
  if (!j) return finish(StopReason::StartFailed, "the start's Jacobian cannot be integrated");
  CurvePoint start = s.point(r.u, r.evaluation, *j, s.tangent(*j, Eigen::VectorXd(), +1));
  start.iterations = r.iterations;

  CurveNode first;
  static_cast<CurvePoint&>(first) = start;
  first.jacobian = *j;
  first.borders = s.borders();
  driver::Options o = driver::step_options(options);  // max_points per half, its start included
  // A chord from the previous point's Jacobian contracts more slowly the longer the step: four
  // or five iterations are its normal pace at steps of a few hundredths.
  o.rule = {4, 1.5, 1.5, 8, 0.7};
  using Result = driver::Result<CurveNode, CurveEvent>;
  // One half, in `direction` of the second parameter, reported with the sign of its direction
  // on its indices; a half that would begin by leaving the window (the start on its edge in the
  // second parameter) is not run.
  const auto half = [&](int direction) {
    const bool on_edge = direction > 0 ? p2 >= options.second_upper : p2 <= options.second_lower;
    CurveNode from = first;
    from.tangent = s.tangent(*j, Eigen::VectorXd(), direction);
    if (on_edge) {
      Result r;
      r.points.push_back(std::move(from));
      r.message = "the start lies on the window's edge";
      return r;
    }
    driver::Callbacks<CurveNode, CurveEvent> cb;
    if (callbacks.on_point)
      cb.on_point = [&](const CurveNode& n) {
        if (n.index == 0) return;  // the start is reported once, before both halves
        CurvePoint q = n;
        q.index *= direction;
        callbacks.on_point(q);
      };
    cb.on_event = callbacks.on_event;
    cb.stop_requested = callbacks.stop_requested;
    CurveContinuation problem(s, curve, options, {event.parameter, p2}, start);
    return driver::continuation(problem, std::move(from), o, cb);
  };
  if (callbacks.on_point) callbacks.on_point(start);
  Result forward = half(+1);
  Result joined;
  if (forward.stop == driver::Stop::Closed || forward.stop == driver::Stop::Interrupted) {
    joined = std::move(forward);
  } else {
    joined = driver::join(half(-1), std::move(forward));
    curve.backward_stop = joined.backward_stop;
  }
  // One curve: the backward half reversed, the start, the forward half (the start's tangent
  // as the curve's, along the forward half).
  for (auto& n : joined.points) {
    CurvePoint& p = n;
    if (p.index == 0) p.tangent = start.tangent;
    curve.points.push_back(std::move(p));
  }
  curve.events = std::move(joined.events);
  return finish(joined.stop, joined.message);
}

PeriodicOrbit curve_point_orbit(const OdeSystem& system, const ParameterValues& base, int first,
                                int second, const CurvePoint& point) {
  PeriodicOrbit orbit;
  orbit.state0 = point.state0;
  orbit.period = point.period;
  orbit.parameters =
      system.with_parameter(system.with_parameter(base, first, point.first), second, point.second);
  orbit.floquet = point.floquet;
  return orbit;
}

}  // namespace sympathy
