#include "sympathy/continuation/bifurcation_curve.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <utility>

#include "curve_system.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

using detail::CriticalBlock;
using detail::CurveSystem;

OptionCheck CurveOptions::validate() const {
  if (!(std::isfinite(first_lower) && std::isfinite(first_upper) && first_lower < first_upper))
    return OptionProblem{"first window", "finite bounds, the lower below the upper"};
  if (!(std::isfinite(second_lower) && std::isfinite(second_upper) && second_lower < second_upper))
    return OptionProblem{"second window", "finite bounds, the lower below the upper"};
  if (!positive(min_step)) return OptionProblem{"min_step", "a positive number"};
  if (!(positive(initial_step) && initial_step >= min_step))
    return OptionProblem{"initial_step", "a positive number, at least the minimum step"};
  if (!(std::isfinite(max_step) && max_step >= initial_step))
    return OptionProblem{"max_step", "a number at least the initial step"};
  if (max_points < 2) return OptionProblem{"max_points", "an integer of at least 2"};
  if (max_iterations < 1) return OptionProblem{"max_iterations", "a positive integer"};
  if (!positive(tolerance)) return OptionProblem{"tolerance", "a positive number"};
  if (!(min_tangent_cosine > 0.0 && min_tangent_cosine < 1.0))
    return OptionProblem{"min_tangent_cosine", "a number in (0, 1)"};
  if (!positive(location_tolerance))
    return OptionProblem{"location_tolerance", "a positive number"};
  return nested("orbit.", orbit.validate());
}

std::string to_string(CurveStop s) {
  switch (s) {
    case CurveStop::WindowEdge:
      return "window edge";
    case CurveStop::Closed:
      return "closed";
    case CurveStop::PointLimit:
      return "point limit";
    case CurveStop::MinimumStep:
      return "minimum step";
    case CurveStop::Interrupted:
      return "interrupted";
    case CurveStop::StartFailed:
      return "start failed";
  }
  return "?";
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

class CurveRun {
 public:
  // `origin`: the event's (first, second) parameters, where the curve was started.
  CurveRun(CurveSystem& system, const BifurcationCurve& curve, const CurveOptions& options,
           const CurveCallbacks& callbacks, std::pair<double, double> origin)
      : system_(system), curve_(curve), options_(options), callbacks_(callbacks), origin_(origin) {}

  // From the corrected start (u, its Jacobian), in `direction` of the second parameter.
  CurveStop run(const CurvePoint& start, const Eigen::MatrixXd& start_jacobian, int direction,
                std::vector<CurvePoint>& points, std::vector<CurveEvent>& events,
                std::string& reason);

 private:
  bool inside(const Eigen::VectorXd& u) const;
  std::vector<Watch> watches() const;
  void detect(const CurvePoint& from, const Eigen::MatrixXd& jacobian, const CurvePoint& to,
              double step, std::vector<CurveEvent>& events);
  CurveEvent locate(const Watch& w, const CurvePoint& from, const Eigen::MatrixXd& jacobian,
                    const CurvePoint& to, double step, double f0, double f1);
  CurveEvent locate_turn(int k, const CurvePoint& from, const Eigen::MatrixXd& jacobian,
                         const CurvePoint& to, double step, double t0);

  CurveSystem& system_;
  const BifurcationCurve& curve_;
  const CurveOptions& options_;
  const CurveCallbacks& callbacks_;
  std::pair<double, double> origin_;
};

bool CurveRun::inside(const Eigen::VectorXd& u) const {
  const double p1 = u[system_.first_index()], p2 = u[system_.second_index()];
  return p1 >= options_.first_lower && p1 <= options_.first_upper && p2 >= options_.second_lower &&
         p2 <= options_.second_upper;
}

std::vector<Watch> CurveRun::watches() const {
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

CurveEvent CurveRun::locate(const Watch& w, const CurvePoint& from, const Eigen::MatrixXd& jacobian,
                            const CurvePoint& to, double step, double f0, double f1) {
  // Regula falsi (Illinois) in the arclength from `from` along its tangent: each probe a point
  // corrected onto the curve under the arclength condition there.
  double a = 0.0, b = step, fa = f0, fb = f1;
  int side = 0;
  CurveEvent e;
  e.type = w.type;
  e.description = w.description;
  CurvePoint best;
  bool have = false;
  for (int probe = 0; probe < 40 && std::abs(b - a) > options_.location_tolerance; ++probe) {
    const double s = (a * fb - b * fa) / (fb - fa);
    const double t = std::clamp(s, a + 0.01 * (b - a), b - 0.01 * (b - a));
    CurveSystem::Condition c;
    c.tangent = from.tangent;
    c.from = from.unknowns;
    c.step = t;
    auto r = system_.correct(from.unknowns + t * from.tangent, c, jacobian);
    if (!r.converged) {
      e.note = "a probe failed: " + r.reason;
      break;
    }
    best = system_.point(r.u, r.evaluation, jacobian, from.tangent);
    have = true;
    const double ft = w.value(best);
    if (!std::isfinite(ft)) break;
    if ((ft < 0.0) == (fa < 0.0)) {
      a = t;
      fa = ft;
      if (side == -1) fb *= 0.5;
      side = -1;
    } else {
      b = t;
      fb = ft;
      if (side == +1) fa *= 0.5;
      side = +1;
    }
    if (ft == 0.0) {
      a = b = t;
    }
  }
  e.located = have && std::abs(b - a) <= options_.location_tolerance;
  if (!have) {
    // No probe converged: where the watched function's chord between the points is zero.
    const double t = f0 / (f0 - f1);
    e.at = t < 0.5 ? from : to;
    e.first = from.first + t * (to.first - from.first);
    e.second = from.second + t * (to.second - from.second);
    e.uncertainty = std::abs(to.first - from.first);
  }
  if (have) {
    e.at = best;
    e.first = best.first;
    e.second = best.second;
    // The bracket's width in the first parameter, and the point's own uncertainty.
    const double speed = std::abs(from.tangent[system_.first_index()]);
    e.uncertainty = std::abs(b - a) * speed + best.uncertainty;
  }
  if (w.type == "other") {
    // Name it by the crossing multiplier (at the point after it, where no probe converged).
    const CurvePoint& named = have ? best : to;
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

CurveEvent CurveRun::locate_turn(int k, const CurvePoint& from, const Eigen::MatrixXd& jacobian,
                                 const CurvePoint& to, double step, double t0) {
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
  // The vertex in the arclength is fixed only to about the square root of the points' noise over
  // the curvature (1e-9 noise: some 3e-5), however many probes: narrowed to 1e-7 at most, and
  // the uncertainty says how far it got (the turned parameter's value is fixed far better).
  const double tolerance = std::max(options_.location_tolerance, 1e-7);
  double t = t0, previous = step;
  bool have = false;
  for (int probe = 0; probe < 12; ++probe) {
    t = std::clamp(t, 0.0, step);
    CurveSystem::Condition c;
    c.tangent = from.tangent;
    c.from = from.unknowns;
    c.step = t;
    const auto r = system_.correct(from.unknowns + t * from.tangent, c, jacobian);
    if (!r.converged) {
      e.note = "a probe failed: " + r.reason;
      break;
    }
    samples.push_back({t, system_.point(r.u, r.evaluation, jacobian, from.tangent)});
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

void CurveRun::detect(const CurvePoint& from, const Eigen::MatrixXd& jacobian, const CurvePoint& to,
                      double step, std::vector<CurveEvent>& events) {
  for (const auto& w : watches()) {
    const double f0 = w.value(from), f1 = w.value(to);
    if (!(std::isfinite(f0) && std::isfinite(f1)) || (f0 < 0.0) == (f1 < 0.0)) continue;
    if (f0 == 0.0) continue;  // found at the previous step
    CurveEvent e = locate(w, from, jacobian, to, step, f0, f1);
    e.after_point = from.index;
    events.push_back(e);
    if (callbacks_.on_event) callbacks_.on_event(events.back());
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
      CurveEvent e = locate(w, from, jacobian, to, step, f0, f1);
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
      if (callbacks_.on_event) callbacks_.on_event(events.back());
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
    CurveEvent turn = locate_turn(k, from, jacobian, to, step, step * a / (a - b));
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
    if (callbacks_.on_event) callbacks_.on_event(events.back());
  }
}

CurveStop CurveRun::run(const CurvePoint& start, const Eigen::MatrixXd& start_jacobian,
                        int direction, std::vector<CurvePoint>& points,
                        std::vector<CurveEvent>& events, std::string& reason) {
  CurvePoint here = start;
  Eigen::MatrixXd jacobian = start_jacobian;
  here.tangent = system_.tangent(jacobian, Eigen::VectorXd(), direction);
  double step = options_.initial_step;
  double farthest = 0.0;
  for (int count = 1;; ++count) {
    if (callbacks_.stop_requested && callbacks_.stop_requested()) {
      reason = "interrupted";
      return CurveStop::Interrupted;
    }
    if (count > options_.max_points) {
      reason = "reached the point limit (" + std::to_string(options_.max_points) + ")";
      return CurveStop::PointLimit;
    }
    system_.set_section(here.unknowns);
    CurveSystem::Correction r;
    bool edge = false;
    while (true) {
      if (step < options_.min_step) {
        reason = "the step fell below the minimum at " + curve_.first_name + " = " +
                 format_number(here.first) + ", " + curve_.second_name + " = " +
                 format_number(here.second) + (r.reason.empty() ? "" : " (" + r.reason + ")");
        return CurveStop::MinimumStep;
      }
      CurveSystem::Condition c;
      c.tangent = here.tangent;
      c.from = here.unknowns;
      c.step = step;
      r = system_.correct(here.unknowns + step * here.tangent, c, jacobian);
      if (r.converged && !inside(r.u)) {
        // Onto the window's edge: the parameter that left it, held at its bound.
        const Eigen::VectorXd& u = r.u;
        const int i1 = system_.first_index(), i2 = system_.second_index();
        CurveSystem::Condition e;
        if (u[i1] < options_.first_lower || u[i1] > options_.first_upper) {
          e.index = i1;
          e.value = u[i1] < options_.first_lower ? options_.first_lower : options_.first_upper;
        } else {
          e.index = i2;
          e.value = u[i2] < options_.second_lower ? options_.second_lower : options_.second_upper;
        }
        const double t = (e.value - here.unknowns[e.index]) / (u[e.index] - here.unknowns[e.index]);
        r = system_.correct(here.unknowns + t * (u - here.unknowns), e, jacobian);
        edge = r.converged;
        if (!r.converged) {
          step *= 0.5;
          continue;
        }
      }
      if (!r.converged) {
        step *= 0.5;
        continue;
      }
      break;
    }
    // The borders moved to the new point's null vectors first, so that its Jacobian (the chord
    // of the next step) has g's row under the borders that step will use.
    const BorderedSingularity previous_borders = system_.borders();
    system_.update_borders(r.evaluation);
    system_.assemble(r.u, r.evaluation);
    const auto next_jacobian = system_.jacobian(r.u, r.evaluation);
    if (!next_jacobian) {
      system_.set_borders(previous_borders);
      step *= 0.5;
      if (step < options_.min_step) {
        reason = "a difference of the Jacobian could not be integrated";
        return CurveStop::MinimumStep;
      }
      continue;
    }
    const Eigen::VectorXd t = system_.tangent(*next_jacobian, here.tangent);
    if (!edge && system_.dot(t, here.tangent) < options_.min_tangent_cosine &&
        step > options_.min_step * 2) {
      system_.set_borders(previous_borders);
      step *= 0.5;
      continue;
    }
    CurvePoint next = system_.point(r.u, r.evaluation, *next_jacobian, t);
    next.index = direction * static_cast<int>(points.size() + 1);
    next.step = edge ? system_.norm(r.u - here.unknowns) : step;
    next.iterations = r.iterations;
    if (options_.detect) detect(here, jacobian, next, next.step, events);
    points.push_back(next);
    if (callbacks_.on_point) callbacks_.on_point(points.back());
    if (edge) {
      reason = "reached the edge of the window at " + curve_.first_name + " = " +
               format_number(next.first) + ", " + curve_.second_name + " = " +
               format_number(next.second);
      return CurveStop::WindowEdge;
    }
    // Back at the start: the curve went away from it and the last step passed through it
    // (within a tenth of the step: a curve's chord misses it by about step^2 times its
    // curvature). A point merely near the start in the scaled norm is not enough: two NS points
    // 6 N/m apart on a 1-100 N/m window are 0.06 apart, about one step.
    const double distance = system_.norm(next.unknowns - start.unknowns);
    farthest = std::max(farthest, distance);
    const Eigen::VectorXd chord = next.unknowns - here.unknowns;
    const double along = std::clamp(
        system_.dot(start.unknowns - here.unknowns, chord) / system_.dot(chord, chord), 0.0, 1.0);
    const double miss = system_.norm(here.unknowns + along * chord - start.unknowns);
    if (farthest > 4.0 * options_.max_step && miss < 0.1 * system_.norm(chord)) {
      reason = "closed: back at the start";
      return CurveStop::Closed;
    }
    here = next;
    jacobian = *next_jacobian;
    // A chord from the previous point's Jacobian contracts more slowly the longer the step:
    // four or five iterations are its normal pace at steps of a few hundredths.
    if (r.iterations <= 4) step = std::min(step * 1.5, options_.max_step);
    if (r.iterations >= 8) step *= 0.7;
  }
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
  Eigen::VectorXd u = s.unknowns_of(event.state0, event.period, event.parameter, p2);
  s.set_scales(u);
  s.set_section(u);
  const auto finish = [&](CurveStop stop, std::string reason) {
    curve.stop = stop;
    curve.stop_reason = std::move(reason);
    curve.flow = s.statistics();
    curve.evaluations = s.evaluations();
    curve.seconds = clock.seconds();
    return curve;
  };
  // The event onto the augmented system at its own second parameter: only the first moves.
  auto e = s.evaluate(u);
  if (!e.ok) return finish(CurveStop::StartFailed, "the event cannot be integrated: " + e.failure);
  s.measure_noise(u, e);
  curve.noise = s.noise();
  auto j = s.jacobian(u, e);
  if (!j) return finish(CurveStop::StartFailed, "the event's Jacobian cannot be integrated");
  CurveSystem::Condition hold;
  hold.index = s.second_index();
  hold.value = p2;
  auto r = s.correct(u, hold, *j);
  if (!r.converged)
    return finish(CurveStop::StartFailed, "the event is not corrected onto the " +
                                              to_string(event.type) + " curve: " + r.reason);
  s.update_borders(r.evaluation);
  s.assemble(r.u, r.evaluation);
  j = s.jacobian(r.u, r.evaluation);
  if (!j) return finish(CurveStop::StartFailed, "the start's Jacobian cannot be integrated");
  const BorderedSingularity start_borders = s.borders();
  CurvePoint start = s.point(r.u, r.evaluation, *j, s.tangent(*j, Eigen::VectorXd(), +1));
  start.iterations = r.iterations;

  CurveCallbacks quiet = callbacks;
  CurveRun run(s, curve, options, quiet, {event.parameter, p2});
  std::vector<CurvePoint> backward, forward;
  std::vector<CurveEvent> backward_events, forward_events;
  std::string forward_reason, backward_reason;
  if (callbacks.on_point) callbacks.on_point(start);
  // A half that would begin by leaving the window (the start on its edge in the second
  // parameter, the direction each half is oriented by) is not run.
  const auto on_edge = [&](int direction) {
    return direction > 0 ? p2 >= options.second_upper : p2 <= options.second_lower;
  };
  const std::string edge_reason = "the start lies on the window's edge";
  CurveStop forward_stop = CurveStop::WindowEdge;
  if (on_edge(+1))
    forward_reason = edge_reason;
  else
    forward_stop = run.run(start, *j, +1, forward, forward_events, forward_reason);
  CurveStop backward_stop = CurveStop::Closed;
  if (forward_stop != CurveStop::Closed && forward_stop != CurveStop::Interrupted) {
    s.set_section(start.unknowns);
    s.set_borders(start_borders);
    backward_stop = CurveStop::WindowEdge;
    if (on_edge(-1))
      backward_reason = edge_reason;
    else
      backward_stop = run.run(start, *j, -1, backward, backward_events, backward_reason);
  }
  // One curve: the backward half reversed, the start, the forward half.
  for (auto it = backward.rbegin(); it != backward.rend(); ++it) curve.points.push_back(*it);
  curve.points.push_back(start);
  for (auto& p : forward) curve.points.push_back(p);
  for (auto it = backward_events.rbegin(); it != backward_events.rend(); ++it)
    curve.events.push_back(*it);
  for (auto& ev : forward_events) curve.events.push_back(ev);
  if (forward_stop == CurveStop::Closed || forward_stop == CurveStop::Interrupted)
    return finish(forward_stop, forward_reason);
  curve.backward_stop = backward_stop;
  const CurveStop stop =
      backward_stop == CurveStop::Interrupted ? CurveStop::Interrupted : forward_stop;
  return finish(stop, "backward: " + backward_reason + "; forward: " + forward_reason);
}

}  // namespace sympathy
