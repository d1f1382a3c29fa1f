// Two-parameter curves of bifurcations of periodic orbits (LP, BP, PD, NS), each from a located
// point of a one-parameter branch, followed in a second parameter by pseudo-arclength
// continuation of a minimally augmented system (continuation/curve_test_function.hpp):
//
//   unknowns  U = (y, T, p1, p2): the orbit's initial state in its subspace's coordinates
//             (y = V^T z, V an orthonormal basis of the subspace the start declared; the whole
//             space if none), its period and both parameters;
//   equations V^T Phi_T(V y; p) - y = 0, a phase condition, and g = 0, the bordered test
//             function of the critical block's matrix:
//               BP  B - I with B = C^T M C, the block of the monodromy M across the subspace
//                   (C its orthonormal complement): every BP of the paper's cases is a
//                   symmetry-breaking pitchfork, and a bordered system in the whole space is
//                   singular all along such a curve, so the orbit stays in its subspace and the
//                   singularity is asked of the breaking block alone;
//               PD  B + I, NS  exterior_square(B) - I, B the block the event's crossing belongs
//                   to (across where it breaks the symmetry, inside otherwise);
//               LP  the shooting Jacobian in the subspace, [V^T M V - I, V^T f; n^T, 0].
//
// The shooting rows' derivatives come from the flow's sensitivities; CVODES has none of second
// order, so g's derivatives (and the parameter columns) are differences of monodromies: the
// Jacobian is formed by forward differences (step 1e-5 in the scaled norm; g's own noise, the
// monodromy's error of about 1e-9, leaves it 1e-4 accurate) once per accepted point, and Newton
// iterates on it as a chord, one monodromy per iteration. Its error slows Newton and never moves
// the point, which only the residual decides.
//
// Along each curve every point carries its multipliers, the critical one(s), for NS the
// rotation number, its residual and trivial-multiplier error, and the uncertainty of its first
// parameter at fixed second (the multipliers' error over the critical multiplier's speed, as for
// located events). Codimension-two points are detected between points and located along the
// curve: the strong resonances of an NS curve (1:1, 1:2, 1:3, 1:4: the pair at angle 0, pi,
// 2 pi / 3, pi / 2), the curve meeting another bifurcation (a multiplier other than the critical
// ones crossing the unit circle: "BP-NS" on a BP curve meeting an NS curve), and the curve
// turning back in either parameter.
#pragma once

#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/continuation_options.hpp"

namespace sympathy {

struct CurveOptions {
  // The window in both parameters: the curve stops on its edge.
  double first_lower = 0.0, first_upper = 0.0;
  double second_lower = 0.0, second_upper = 0.0;
  double initial_step = 0.01;  // scaled arclength: parameters by the window's widths
  double min_step = 1e-5;
  double max_step = 0.05;
  int max_points = 200;              // per half, its start included
  int max_iterations = 12;           // chord iterations per point
  double tolerance = 1e-9;           // |shooting residual|_inf, as the corrector's
  double min_tangent_cosine = 0.95;  // between consecutive tangents, else the step is halved
  double location_tolerance = 1e-9;  // of codimension-two points: arclength (scaled)
  bool detect = true;                // codimension-two points
  // Periods at which to report the curve's orbit (AUTO's UZ on PERIOD), events "UZ" located on
  // the one locator; one with `stop` ends the curve there (UZSTOP). Period only: a curve's
  // points carry no samples of their orbits.
  std::vector<UserValue> user_values;
  // The point of the parameter plane the curve was born from where its orbits shrink into an
  // equilibrium (a fold of cycles from a generalized Hopf point: generalized_hopf.hpp). The
  // curve ends when it comes within end_radius of it, in the parameters scaled by the window's
  // widths: there the fold degenerates, and its corrector crawls (AUTO's fhn: 200 points over
  // the last 0.3% of c). end_radius 0: none.
  double end_first = 0.0, end_second = 0.0, end_radius = 0.0;
  std::string end_name;  // for the message: "the generalized Hopf point"
  OrbitOptions orbit;    // the shooting flow, Floquet options

  OptionCheck validate() const;
};

struct CurvePoint {
  int index = 0;                     // negative on the backward half
  double first = 0.0, second = 0.0;  // the two parameters' values
  double period = 0.0;
  Eigen::VectorXd state0;  // whole state
  FloquetAnalysis floquet;
  // The critical multiplier(s): BP, PD, LP one; NS the pair (mu, conj mu), or a real pair mu,
  // 1 / mu where the curve has become one of neutral saddles.
  std::vector<std::complex<double>> critical;
  // NS: the pair's angle over 2 pi, in [0, 1/2]; NaN elsewhere and on neutral saddles.
  double rotation = std::numeric_limits<double>::quiet_NaN();
  bool neutral_saddle = false;  // NS curve: the pair is real here (mu, 1 / mu)
  double test = 0.0;            // the test function g
  double residual = 0.0;        // |shooting residual|_inf
  // How far the first parameter may lie from the true curve at this second parameter: the
  // multipliers' error (trivial_error) over the critical multiplier's speed in it.
  double uncertainty = 0.0;
  double step = 0.0;  // scaled arclength from the previous point
  int iterations = 0;
  Eigen::VectorXd unknowns;  // U = (y, T, p1, p2)
  Eigen::VectorXd tangent;   // unit, scaled norm
  // What the model's OrbitDescriber says of the orbit (its maxima, minima, ...), where the
  // caller described it (curve_point_orbit); empty otherwise.
  std::vector<double> description;
};

struct CurveEvent {
  // "R1" .. "R4" (strong resonances on an NS curve); "<curve>-<other>" where another multiplier
  // crosses the unit circle ("BP-NS": this BP curve meets an NS curve); "turn in <name>".
  std::string type;
  std::string description;  // for people ("1:2 resonance: the pair at -1")
  double first = 0.0, second = 0.0;
  double uncertainty = 0.0;  // in the first parameter: bracket and the multipliers' error
  CurvePoint at;             // the located point
  // Where another multiplier crosses ("BP-NS"): the symmetry of its perturbations, which says
  // in which block the other curve through the point lives.
  SymmetryKind crossing_symmetry = SymmetryKind::Unlabelled;
  bool located = false;
  int after_point = 0;
  std::string note;
};

struct CurveCallbacks {
  std::function<void(const CurvePoint&)> on_point;
  std::function<void(const CurveEvent&)> on_event;
  std::function<bool()> stop_requested;
};

struct BifurcationCurve {
  BifurcationType kind = BifurcationType::BranchPoint;
  std::string first_name, second_name;
  int first = -1, second = -1;  // parameter indices
  std::vector<std::string> state_names;
  std::string subspace;  // the subspace the orbits are kept in ("" for the whole space)
  // Whether the critical multipliers break the subspace's symmetry (the event's label).
  SymmetryKind symmetry = SymmetryKind::Unlabelled;
  std::vector<CurvePoint> points;  // in order along the curve
  std::vector<CurveEvent> events;
  StopReason stop = StopReason::ParameterBound;
  std::string stop_reason;
  std::optional<StopReason> backward_stop;
  std::string origin;  // "BP at k = 47.0655622456"
  double seconds = 0.0;
  FlowStatistics flow;
  int evaluations = 0;  // monodromies computed
  // The integration's noise measured at the start: |M f(z0) - f(z(T))| / |f(z0)|; above 1e-8 the
  // corrector's difference step and tolerances grow with it (continuation/curve_system.hpp).
  double noise = 0.0;
  CurveOptions options;
  ParameterValues start_values;
  bool started() const { return stop != StopReason::StartFailed; }
};

// The curve of `event` (a located LP, BP, PD or NS of `branch`, a branch of `system`) in the
// branch's parameter and `second` (a parameter index), both ways from the event. Throws
// std::invalid_argument for an event that is not located, a BP without a subspace it breaks, a
// second parameter equal to the first, a window that does not contain the event, or options
// that do not validate.
BifurcationCurve continue_curve(const OdeSystem& system, const Branch& branch,
                                const Bifurcation& event, int second, const CurveOptions& options,
                                const CurveCallbacks& callbacks = {});

// The orbit of a curve's point, for an OrbitDescriber: its state and period at the point's two
// parameter values (`base` the other parameters', the curve's start_values).
PeriodicOrbit curve_point_orbit(const OdeSystem& system, const ParameterValues& base, int first,
                                int second, const CurvePoint& point);

}  // namespace sympathy
