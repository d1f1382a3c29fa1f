// The options of a pseudo-arclength continuation run, their defaults (each set here and nowhere
// else) and their validation. A Branch keeps the options that made it.
#pragma once

#include <vector>

#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy {

// A value of a quantity of a branch's orbits: the period (located exactly: the orbit there is
// corrected with its period held at the value), or a state's largest or smallest value over the
// period (located on the one locator, from the period's samples). `stop`: the branch ends there.
struct UserValue {
  // AtSection: a state's value at the orbit's point on its phase section (state0; for a forced
  // system, at t = 0), AUTO's U(i) at the start of the period.
  // Parameter: one of a two-parameter curve's parameters (a branch's own values are its
  // user_points).
  enum class Quantity { Period, Maximum, Minimum, AtSection, Parameter };
  Quantity quantity = Quantity::Period;
  int state = -1;      // Maximum, Minimum, AtSection: the state's index
  int parameter = -1;  // Parameter: the parameter's index
  double value = 0.0;
  bool stop = false;
  std::string name;  // as the outputs name the quantity: "period", "max_x", "min_x", "x"
};

struct ContinuationOptions {
  double lower = 0.0, upper = 0.0;  // parameter bounds; the run stops when it leaves them
  double initial_step = 0.02;       // scaled arclength
  double min_step = 1e-6;
  double max_step = 0.1;
  double max_parameter_step = 0.0;  // |dp| per step; 0: (upper - lower) / parameter_steps
  double parameter_steps = 25.0;    // at least this many steps over the range (unless the above)
  int max_points = 400;
  int max_corrector_iterations = 7;
  int max_chord_steps = 6;  // before them, on plain integrations (0: Newton from the start)
  double corrector_tolerance = 1e-9;  // |F|_inf, as NewtonOptions::residual_tolerance
  // Per step, the largest change of the modulus of a multiplier within `watch_band` of the unit
  // circle (only those can cross it and come back between two points).
  double max_modulus_change = 0.02;
  double watch_band = 0.1;
  // Smallest cosine between consecutive unit tangents: a step that turns the tangent more is
  // halved, so that orientation (and hence direction along the branch) stays unambiguous.
  double min_tangent_cosine = 0.9;
  double location_tolerance = 1e-8;  // relative, in the parameter
  double trust_limit = 1e-6;         // trivial-multiplier error above which events are flagged
  bool detect_bifurcations = true;
  bool curved_predictor = true;  // cubic through the last two points; false: the tangent alone
  // Values of the parameter at which the branch reports its orbit (AUTO's UZ): each time the
  // branch passes one, the point there, corrected with the parameter fixed at it, is an event of
  // type UserPoint. Finite and distinct; any order. The start itself is not reported.
  std::vector<double> user_points;
  // Values of a quantity of the orbits at which the branch reports its orbit, or stops there
  // (AUTO's UZ and UZSTOP on any quantity), each as an event of type UserPoint.
  std::vector<UserValue> user_values;
  OrbitOptions orbit;  // shooting, rank tolerance, stability tolerance

  // The bounds are not checked here (a branch run sets them from its problem; the Continuation
  // checks lower < upper).
  OptionCheck validate() const;
};

}  // namespace sympathy
