// Where a branch of hybrid orbits changes which switching surfaces its orbits cross.
//
// A periodic orbit of a piecewise-smooth system (core/hybrid_system.hpp) crosses its switching
// surfaces a fixed number of times a period while it stays away from tangency; along a branch
// that number changes only where an orbit touches a surface tangentially (a grazing: two
// crossings appear or vanish together) or starts to slide along one (the flow refuses that,
// core/saltation.hpp). At the grazing orbit the flow has no derivative, so the branch's
// saltation-based monodromy and everything built on it (multipliers, events) ends there: the
// driver's orbit problem compares the crossings of consecutive points and, where they differ,
// locates the change by bisection along the step and ends the branch (StopReason::Nonsmooth).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy {

// How often the orbit crosses each switching surface in one period from its state0 (one plain
// run of the flow at the given options); empty for a system that is not a hybrid one with
// surfaces.
std::vector<int> crossings_per_period(const OdeSystem& system, const FlowOptions& flow,
                                      const PeriodicOrbit& orbit);

// "th1 = the crossed 2 -> 0 times a period" for each surface whose count differs (named by the
// system's switching_name).
std::string describe_crossing_change(const OdeSystem& system, const std::vector<int>& before,
                                     const std::vector<int>& after);

// Where along a step of length `length` (its arclength) the crossings per period change from
// `before`: bisection, probe(s, why) giving the crossings of the point corrected at arclength s
// (nullopt where it could not be had, `why` saying why: the bisection ends there), until
// narrow(near, far) or 60 probes. Bisection, not a secant on a test function: the count is an
// integer, and the tangency it changes at has no smooth measure common to every surface. The one
// location of a grazing, for branches (Continuation::crossing_change) and curves.
struct CrossingBracket {
  double near = 0.0, far = 0.0;  // the last probes with `before`'s crossings and with others
  std::string failed;            // why a probe failed, if one did
};
CrossingBracket bisect_crossing_change(
    double length, const std::vector<int>& before,
    const std::function<std::optional<std::vector<int>>(double, std::string&)>& probe,
    const std::function<bool(double, double)>& narrow);

// A change of the crossings located between two points of a branch: the parameter bracket of
// the last probe before it and the first after it.
struct CrossingChange {
  double parameter = 0.0;    // the bracket's middle
  double uncertainty = 0.0;  // half its width
  double arclength = 0.0;    // of the bracket's far end from the step's start
  std::string note;          // which surfaces, how many crossings before and after
  bool located = true;       // false: a probe failed before the bracket reached the tolerance
};

}  // namespace sympathy
