// The one pseudo-arclength continuation driver: its public surface, PROPOSED for review (issue 33,
// item 2; to be agreed with the application layer's requests, issue 34, before any code moves).
// Nothing in the engine uses this header yet: today orbits (Continuation::run_from), two-parameter
// curves (CurveRun) and equilibria (equilibrium_branch.cpp's Run) each have their own step loop,
// retry and step rules, Illinois locator, two-way join, stop enumeration (StopReason, CurveStop,
// EquilibriumStop), callbacks and scaled norm. The move, one problem at a time (equilibria, then
// curves, then orbits), replaces them with `continuation()` below; the goldens, the step-sequence
// test and tests/auto hold at each move.
//
// The split is BifurcationKit's (a problem, continuation parameters and the result as separate
// values; one `continuation` for every problem) and AUTO's (AUTOAE/AUTOBV: one driver, the
// problem supplying its equations): the driver owns the step loop, prediction, the call to the
// problem's corrector, retries by cause and the step rule, bounds and window edges, event
// bracketing and the one locator, both ways and the join, the stop enumeration and the callbacks;
// a problem owns what only it knows: its unknowns and their scaled norm, correction, tangent,
// test functions and a point at an arclength for location. Values travel with the points (the
// phase section with a periodic orbit's point, parameter values with every point): nothing is
// written into a shared object, so one problem serves runs side by side.
//
// Detection keeps, beside each problem's test functions, what a stability verdict rests on and
// no collision off the circle can change (for orbits: the number of multipliers outside the unit
// circle, sign prod(mu - 1) and sign prod(mu + 1) over the nontrivial ones; for equilibria: the
// eigenvalues in the right half plane and sign det J). A change the test functions do not explain
// refines the step or becomes an Unresolved event between the two points: no crossing passes
// silently. (The two sign rules already guard today's orbit detector, detection.cpp.)
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/option_check.hpp"

namespace sympathy::driver {

// Why a run ended: one enumeration for every problem (callers switch on it; `Result::message`
// says it for people, with numbers).
enum class Stop {
  Bound,        // the parameter left the window asked for (the normal end)
  PointLimit,   // max_points reached
  MinimumStep,  // the step fell below min_step: the corrector kept failing (its reason kept)
  Interrupted,  // Callbacks::stop_requested said so
  StartFailed,  // no starting point
  ProblemEnd,   // the problem says the branch ends here (an orbit family at its Hopf point,
                // a curve at a degenerate point), with its reason
  Retraced,     // the branch came back onto itself (checked on the points, not on a turn)
};
std::string to_string(Stop s);

// What is continued. Implemented by the periodic-orbit, equilibrium and two-parameter-curve
// problems; the driver never looks inside a point but through these.
template <class Point>
class Problem {
 public:
  virtual ~Problem() = default;

  // The unknowns (the parameter last) of a point, and the scaled inner product in which
  // arclength, tangents and step lengths are measured (a problem widens its scales as the
  // branch meets larger amplitudes: `widen`).
  virtual Eigen::VectorXd unknowns(const Point& p) const = 0;
  virtual double dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const = 0;
  virtual void widen(const Point& p) = 0;

  // The point on the branch through `prediction` on the hyperplane orthogonal to `tangent` at
  // arclength `step` from `from`; nullopt with the reason in `why` when the correction fails.
  // The problem's own corrector (Newton, chords, Broyden) and its convergence rule (for orbits,
  // closure to kOrbitClosure of the amplitude as well) live here.
  virtual std::optional<Point> correct(const Point& from, const Eigen::VectorXd& tangent,
                                       double step, const Eigen::VectorXd& prediction,
                                       std::string& why) = 0;
  // The unit tangent at `p`, oriented along `along`.
  virtual Eigen::VectorXd tangent(const Point& p, const Eigen::VectorXd& along) const = 0;

  // The test functions at `p` (fold: the tangent's parameter component; each crossing's its own)
  // and what the stability verdict rests on there.
  struct Tests {
    std::vector<double> values;         // in a fixed order per problem
    int unstable = 0;                   // multipliers outside the circle / eigenvalues with Re > 0
    int sign_plus = 1, sign_minus = 1;  // sign prod(mu - 1), sign prod(mu + 1) (equilibria:
                                        // sign det J, and 1)
    bool trusted = true;                // the point's own accuracy earns a verdict
  };
  virtual Tests tests(const Point& p) const = 0;
  // The point at arclength `s` from `a` towards `b`, for the locator; nullopt with `why`.
  virtual std::optional<Point> point_at(const Point& a, const Point& b, double s,
                                        std::string& why) = 0;
  // A problem's own end (ProblemEnd) between two accepted points, with its reason; nullopt: go on.
  virtual std::optional<std::string> ends_between(const Point& a, const Point& b) = 0;
};

// The driver's options (the problem's own, such as the shooting's, live with the problem).
// Defaults set here alone; validate() names the field and what is expected.
struct Options {
  double lower = 0.0, upper = 0.0;                              // the parameter's window
  double initial_step = 0.02, min_step = 1e-6, max_step = 0.1;  // scaled arclength
  int max_points = 400;
  double min_tangent_cosine = 0.9;   // a step that turns the tangent more is halved
  double location_tolerance = 1e-8;  // relative, in the parameter
  int location_retries = 3;          // shorter tries of a step whose event was not located
  std::vector<double> user_points;   // AUTO's UZ: the branch's point at each of these values
  OptionCheck validate() const;
};

// What a run reports as it goes: each accepted point and located event, and its position among
// known totals, from which the command line and Python draw progress.
template <class Point, class Event>
struct Callbacks {
  std::function<void(const Point&)> on_point;
  std::function<void(const Event&)> on_event;
  struct Progress {
    int points = 0;        // accepted so far
    double parameter = 0;  // where the branch stands
    double fraction = 0;   // of the window covered, by the parameter (0 .. 1; turns count once)
  };
  std::function<void(const Progress&)> on_progress;
  std::function<bool()> stop_requested;  // polled between points
};

// A run's result: the points and events in order along the branch, why it ended (both parts of
// a two-way run), and what made it. The library, not a front end, joins and reverses results.
template <class Point, class Event>
struct Result {
  std::vector<Point> points;
  std::vector<Event> events;
  Stop stop = Stop::Bound;
  std::string message;
  std::optional<Stop> backward_stop;  // a two-way run's backward part
  std::string backward_message;
  Options options;
  int start_index = 0;  // of the starting point among `points` (> 0 after a join)
};

// The one driver: from `start`, in the direction of `along` (unknowns and parameter), until a
// Stop. Both ways: run it with `along` and with -along, then join.
template <class Point, class Event>
Result<Point, Event> continuation(Problem<Point>& problem, const Point& start,
                                  const Eigen::VectorXd& along, const Options& options,
                                  const Callbacks<Point, Event>& callbacks = {});

// The backward run reversed, then the forward run without its copy of the start: one branch in
// order along it, each part's stop kept.
template <class Point, class Event>
Result<Point, Event> join(Result<Point, Event> backward, Result<Point, Event> forward);

}  // namespace sympathy::driver
