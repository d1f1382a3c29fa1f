// The one pseudo-arclength continuation driver (issue 33, item 2): the step loop every branch
// runs, whatever it continues.
//
// The split is BifurcationKit's (a problem, continuation parameters and the result as separate
// values; one `continuation` for every problem) and AUTO's (AUTOAE/AUTOBV: one driver, the
// problem supplying its equations). The driver owns the step loop, retries by cause and the step
// rule, the window's edge, retries of a step whose event was not located, the stop enumeration,
// the callbacks with progress and the two-way join; the one locator is crossing_locator.hpp's. A
// problem owns what only it knows: its unknowns, prediction and correction, tangent and turn,
// the point on the window's edge, its test functions (located with the one locator), and its own
// ends. Values travel with the points (a curve's borders and chord Jacobian, an orbit's phase
// section and shooting Jacobian): a rejected step leaves no trace on the branch (an orbit's
// problem keeps only what its corrections learnt of how well predictions land).
//
// Every branch runs here: periodic orbits (continuation.cpp's Continuation::Run), equilibria
// (equilibrium_branch.cpp) and two-parameter curves (bifurcation_curve.cpp). Two ends are
// problems' own: an orbit family that turns back into an equilibrium at its Hopf point, and a
// curve that closes on its start. The step rule's constants are each problem's (Options::rule):
// Newton with exact derivatives (equilibria) doubles, a chord (curves) grows 1.5 up to 4
// iterations, an orbit's corrector 1.5 up to 2.
//
// A problem P provides (checked where `continuation` is instantiated):
//   using Point = ...;   // with members `int index`, `int iterations` (and `tangent` to join)
//   using Event = ...;   // with member `int after_point`
//   driver::Attempt<Point> step(const Point* before, const Point& a, double ds);
//       // predicted from a (and the point before it, if any), corrected at arclength ds, its
//       // tangent oriented along a's; the cause and reason when it fails
//   double turn_cosine(const Point& a, const Point& b) const;  // of their tangents, scaled
//   bool outside(const Point& b) const;                          // beyond the window
//   std::string edge_message(const Point& b) const;  // the ParameterBound stop's, naming where
//   std::optional<Point> onto_edge(const Point& a, const Point& b);  // the branch on the edge
//   driver::Found<Event> detect(const Point* before, const Point& a, const Point& b);
//       // the events between a and b, located (with the one locator)
//   std::optional<driver::Ending> ends(const Point& a, const Point& b, std::vector<Event>&);
//       // the problem's own end between a and b (it may drop or add events); nullopt: go on
//   void accept(Point& b);         // b joins the branch (scales widen, the tangent renormalised)
//   double parameter(const Point& p) const;  // for progress
// and where it has a view on them (optional):
//   double limit_step(const Point& a, double ds);  // the step to try from a, at most ds
//   driver::Screen screen(const Point* before, const Point& a, const Point& b, double ds);
//       // the problem's own check of a corrected step (an orbit's multipliers moving too far)
//   bool refine(Point& a, const std::string& why);
//       // where the step fell below the minimum at a: a resolved better (in place), to try again
//       // from the step that reached a (the initial step where a has none); false: the branch
//       // ends there
#pragma once

#include <algorithm>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/option_check.hpp"

namespace sympathy {

// Why a run ended: one enumeration for every branch (orbits, equilibria, curves); callers switch
// on it, and a result's message says it for people, with numbers.
enum class StopReason {
  ParameterBound,  // reached the window's edge (the normal end); the last point lies on it
  PointLimit,      // max_points reached
  MinimumStep,     // the step fell below min_step: the corrector kept failing (its reason kept)
  Interrupted,     // stop_requested said so
  StartFailed,     // no starting point
  TurnedBack,      // an orbit branch turned back without a multiplier at +1 (see
                   // EventTrust::NoCrossingMultiplier): stopped there rather than retrace itself
  HopfPoint,       // an orbit family shrank into an equilibrium at its Hopf point
  Homoclinic,      // an orbit family's period grows without bound as its parameter converges
                   // (homoclinic_approach.hpp)
  Closed,          // a curve came back to its start
  UserValue,       // an orbit branch reached a value it was asked to stop at (UserValue::stop)
  Nonsmooth,       // a branch of hybrid orbits reached a grazing: its orbits' crossings of the
                   // switching surfaces change there (grazing.hpp)
};
std::string to_string(StopReason s);  // "parameter bound", "point limit", ...

}  // namespace sympathy

namespace sympathy::driver {

using Stop = StopReason;

// Why a step was tried again shorter.
enum class Cause {
  Corrector,    // the correction failed
  Turn,         // the tangent turned more than min_tangent_cosine allows
  Edge,         // the point on the window's edge could not be corrected
  Location,     // an event between the points was not located
  Multipliers,  // the problem's own check of the step (multipliers moved too far)
};
constexpr int kCauses = 5;

// How the step grows after an accepted point: by `growth` when the corrector took at most
// `fast_iterations`, by `growth_after_screen` if that step was a retry after the problem's screen
// rejected a longer one (what it watches was just seen moving fast); shrunk by `shrink` when it
// took `slow_iterations` or more; never above max_step nor above the problem's aim.
struct StepRule {
  int fast_iterations = 2;
  double growth = 1.5;
  double growth_after_screen = 1.2;
  int slow_iterations = 5;
  double shrink = 0.6;
};

struct Options {
  double initial_step = 0.02, min_step = 1e-6, max_step = 0.1;  // scaled arclength
  int max_points = 400;                                         // including the start
  double min_tangent_cosine = 0.9;  // a step that turns the tangent more is halved
  int location_retries = 0;         // shorter tries of a step whose event was not located
  StepRule rule;
  OptionCheck validate() const;
};

// The driver's options from a problem's own (each names its step fields alike: initial_step,
// min_step, max_step, max_points, min_tangent_cosine); the rule and retries are the problem's.
template <class ProblemOptions>
Options step_options(const ProblemOptions& p) {
  Options o;
  o.initial_step = p.initial_step;
  o.min_step = p.min_step;
  o.max_step = p.max_step;
  o.max_points = p.max_points;
  o.min_tangent_cosine = p.min_tangent_cosine;
  return o;
}

// Whether x lies on the chord from a to b, within a tenth of the chord's length (a chord misses
// its branch by about step^2 times the curvature), in the problem's scaled inner product `dot`:
// how a branch sees itself come back onto points it has passed (a closed curve, an orbit branch
// retracing itself).
template <class Dot>
bool on_chord(const Eigen::VectorXd& x, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
              const Dot& dot) {
  const Eigen::VectorXd chord = b - a;
  const double length2 = dot(chord, chord);
  if (!(length2 > 0.0)) return false;
  const double along = std::clamp(dot(x - a, chord) / length2, 0.0, 1.0);
  const Eigen::VectorXd miss = a + along * chord - x;
  return dot(miss, miss) < 0.01 * length2;
}

// A step's outcome, from the problem.
template <class Point>
struct Attempt {
  std::optional<Point> point;
  Cause cause = Cause::Corrector;  // why not, when no point
  std::string why;
  // The longest step the problem would take next (a retry, or the step after this one):
  // infinity when it has no view.
  double aim = std::numeric_limits<double>::infinity();
  bool on_edge = false;  // the point lies on the window's edge already (the branch ends there)
};

// The problem's check of a corrected step: rejected (retried at most at `aim`, and never below
// four minimum steps), or accepted with the longest next step it would take.
struct Screen {
  bool reject = false;
  double aim = std::numeric_limits<double>::infinity();
  std::string why;
};

template <class Event>
struct Found {
  std::vector<Event> events;  // in order along the step
  bool unlocated = false;     // one of them could not be located: a shorter step may
};

struct Ending {
  Stop stop = Stop::TurnedBack;
  std::string why;
  bool keep_point = true;  // b joins the branch before it ends
};

// Where a run stands, from which the command line and Python draw progress.
struct Progress {
  int points = 0, max_points = 0;
  double parameter = 0.0;
};

template <class Point, class Event>
struct Callbacks {
  std::function<void(const Point&)> on_point;
  std::function<void(const Event&)> on_event;
  std::function<void(const Progress&)> on_progress;
  std::function<bool()> stop_requested;  // polled between points
};

template <class Point, class Event>
struct Result {
  std::vector<Point> points;  // in order along the branch
  std::vector<Event> events;
  Stop stop = Stop::ParameterBound;
  std::string message;
  std::optional<Stop> backward_stop;  // a joined two-way run's backward part
  int rejected[kCauses] = {};         // steps tried again, by cause
};

// From `start` (corrected, its tangent set in the direction to go) until a Stop.
template <class P, class Point = typename P::Point, class Event = typename P::Event>
Result<Point, Event> continuation(P& problem, Point start, const Options& o,
                                  const Callbacks<Point, Event>& callbacks = {}) {
  Result<Point, Event> r;
  auto finish = [&](Stop stop, std::string message) {
    r.stop = stop;
    r.message = std::move(message);
    return std::move(r);
  };
  auto report = [&](const Point& p) {
    if (callbacks.on_point) callbacks.on_point(p);
    if (callbacks.on_progress)
      callbacks.on_progress(
          {static_cast<int>(r.points.size()), o.max_points, problem.parameter(p)});
  };
  r.points.push_back(std::move(start));
  report(r.points.back());
  double ds = o.initial_step;
  double aim = std::numeric_limits<double>::infinity();
  int location_retries = 0;
  bool retried = false;  // a step the screen rejected was retried shorter (until one is accepted)
  std::string last_failure;
  for (;;) {
    if (callbacks.stop_requested && callbacks.stop_requested())
      return finish(Stop::Interrupted, "interrupted");
    if (static_cast<int>(r.points.size()) >= o.max_points)
      return finish(Stop::PointLimit, "point limit (" + std::to_string(o.max_points) + ") reached");
    if (ds < o.min_step) {
      // The problem may resolve its last point better (an orbit on more shooting segments) and
      // try again before the branch ends here: from the step that reached that point, not the
      // initial one (which on AUTO's tor jumped a period of 1 past a fold and a branch point
      // 0.004 apart right after the refinement).
      if constexpr (requires { problem.refine(r.points.back(), last_failure); }) {
        if (problem.refine(r.points.back(), last_failure)) {
          ds = o.initial_step;
          if constexpr (requires { r.points.back().step; })
            if (r.points.back().step > 0.0)
              ds = std::clamp(r.points.back().step, 4 * o.min_step, o.initial_step);
          continue;
        }
      }
      return finish(Stop::MinimumStep, "step size below the minimum: " + last_failure);
    }
    const Point& a = r.points.back();
    const Point* before = r.points.size() >= 2 ? &r.points[r.points.size() - 2] : nullptr;
    if constexpr (requires { problem.limit_step(a, ds); }) ds = problem.limit_step(a, ds);
    const bool can_shorten = ds > 4 * o.min_step;
    auto retry = [&](Cause cause, std::string why, double aimed) {
      ++r.rejected[static_cast<int>(cause)];
      last_failure = std::move(why);
      ds = std::min(0.5 * ds, aimed);
      // The multipliers' aim may ask for far less than half; never below what can be shortened.
      if (cause == Cause::Multipliers) {
        ds = std::max(ds, 4 * o.min_step);
        retried = true;
      }
    };
    Attempt<Point> attempt = problem.step(before, a, ds);
    if (!attempt.point) {
      retry(attempt.cause, attempt.why, attempt.aim);
      continue;
    }
    Point b = std::move(*attempt.point);
    if (can_shorten && problem.turn_cosine(a, b) < o.min_tangent_cosine) {
      retry(Cause::Turn, "the tangent turned too far", attempt.aim);
      continue;
    }
    double aim_next = attempt.aim;
    if constexpr (requires { problem.screen(before, a, b, ds); }) {
      Screen screen = problem.screen(before, a, b, ds);
      if (screen.reject && can_shorten) {
        retry(Cause::Multipliers, screen.why, std::min(screen.aim, attempt.aim));
        continue;
      }
      aim_next = std::min(aim_next, screen.aim);
    }
    bool on_edge = attempt.on_edge;
    if (!on_edge && problem.outside(b)) {
      if (auto edge = problem.onto_edge(a, b)) {
        b = std::move(*edge);
        on_edge = true;
      } else if (can_shorten) {
        retry(Cause::Edge, "the point on the window's edge could not be corrected", attempt.aim);
        continue;
      }
    }
    b.index = a.index + 1;
    Found<Event> found = problem.detect(before, a, b);
    if (found.unlocated && location_retries < o.location_retries && can_shorten) {
      ++location_retries;
      retry(Cause::Location, "an event was not located", attempt.aim);
      continue;
    }
    location_retries = 0;
    std::optional<Ending> ending = problem.ends(a, b, found.events);
    const int iterations = b.iterations;
    // (a and before are not used past here: the push may move the points.)
    if (!ending || ending->keep_point) {
      r.points.push_back(std::move(b));
      report(r.points.back());
    }
    for (auto& e : found.events) {
      r.events.push_back(std::move(e));
      if (callbacks.on_event) callbacks.on_event(r.events.back());
    }
    if (ending) return finish(ending->stop, ending->why);
    if (on_edge || problem.outside(r.points.back()))
      return finish(Stop::ParameterBound, problem.edge_message(r.points.back()));
    problem.accept(r.points.back());
    aim = aim_next;
    const StepRule& rule = o.rule;
    if (iterations <= rule.fast_iterations)
      ds = std::min((retried ? rule.growth_after_screen : rule.growth) * ds, o.max_step);
    else if (iterations >= rule.slow_iterations)
      ds *= rule.shrink;
    ds = std::max(std::min(ds, aim), std::min(ds, 4 * o.min_step));
    retried = false;
  }
}

// One branch from a two-way run: the backward part reversed (indices negated, each event placed
// after the point before it in the new order), the start once, then the forward part. Points
// need `index` and `tangent` (reversed), events `after_point`.
template <class Point, class Event>
Result<Point, Event> join(Result<Point, Event> backward, Result<Point, Event> forward) {
  Result<Point, Event> r;
  for (auto it = backward.points.rbegin(); it != backward.points.rend(); ++it) {
    if (it->index == 0) continue;  // the start, kept from the forward part
    Point q = std::move(*it);
    q.index = -q.index;
    q.tangent = -q.tangent;
    r.points.push_back(std::move(q));
  }
  for (auto& p : forward.points) r.points.push_back(std::move(p));
  for (auto it = backward.events.rbegin(); it != backward.events.rend(); ++it) {
    Event e = std::move(*it);
    e.after_point = -e.after_point - 1;
    r.events.push_back(std::move(e));
  }
  for (auto& e : forward.events) r.events.push_back(std::move(e));
  r.stop = backward.stop == Stop::Interrupted ? backward.stop : forward.stop;
  r.backward_stop = backward.stop;
  r.message = "backward: " + backward.message + "; forward: " + forward.message;
  for (int i = 0; i < kCauses; ++i) r.rejected[i] = backward.rejected[i] + forward.rejected[i];
  return r;
}

}  // namespace sympathy::driver
