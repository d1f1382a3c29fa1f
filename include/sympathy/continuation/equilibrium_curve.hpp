// Curves of the folds (LP) and Hopf points (HB) of equilibria in two parameters, as AUTO's ISW = 2
// from an LP or HB label of an equilibria run and MatCont's LP and H curves, run by the one
// driver (driver.hpp).
//
// Unknowns Y = (x, p1, p2) for a fold curve, (x, p1, p2, kappa) for a Hopf curve, on minimally
// augmented systems (Govaerts, "Numerical Methods for Bifurcations of Dynamical Equilibria",
// SIAM 2000, ch. 4; MatCont's):
//   LP: f = 0 and g = 0, g from [A b; c^T 0] [v; g] = [0; 1] (A = f_x): zero exactly where A is
//       singular, regular at a simple fold;
//   HB: f = 0 and two entries of G from [A^2 + kappa I, B; C^T, 0] [V; G] = [0; I_2]: A^2 + kappa I
//       has a two-dimensional kernel where A has the eigenvalues +-i sqrt(kappa) (kappa > 0: a
//       Hopf point, omega = sqrt(kappa)) or +-sqrt(-kappa) (kappa < 0: a neutral saddle, which
//       the same test finds: told apart by kappa's sign, labelled, never a start of cycles). The
//       two entries are the pair that keeps the system's Jacobian best conditioned, chosen anew
//       at every point.
// The borders b, c (B, C) are the previous point's null vectors, renewed at every point. f's rows
// of the Jacobian are exact (the system's dual numbers), g's central differences of the bordered
// solves (step 1e-6 in the scaled norm: error about 1e-12 relative; Newton converges to rounding).
//
// Codimension-two points, each a test function located by the one locator:
//   on an LP curve: BT (Bogdanov-Takens: <w, v> = 0, the zero eigenvalue's left and right null
//       vectors orthogonal, so it is double), CP (cusp: the fold's quadratic coefficient
//       <w, f_xx[v, v]> = 0), ZH (zero-Hopf: the real parts of the other eigenvalues' complex
//       pairs, multiplied);
//   on an HB curve: BT (kappa = 0, where the Hopf curve turns into a neutral-saddle one), GH
//       (generalized Hopf: the first Lyapunov coefficient l1 = 0, on the Hopf part), ZH (a real
//       eigenvalue through zero: det A / kappa), HH (double Hopf: another pair through the axis).
// At each its normal-form coefficients (codim2_coefficients.hpp).
#pragma once

#include <complex>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/driver.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"

namespace sympathy {

struct EquilibriumCurveOptions {
  double first_lower = 0.0, first_upper = 0.0;    // the window in the branch's parameter
  double second_lower = 0.0, second_upper = 0.0;  // and in the second
  double initial_step = 0.01;                     // scaled arclength
  double min_step = 1e-7;
  double max_step = 0.05;
  int max_points = 1000;  // per direction
  int max_iterations = 8;
  double tolerance = 1e-11;  // of Newton's last step, relative to max(1, |Y|_inf)
  double min_tangent_cosine = 0.95;
  double location_tolerance = 1e-9;  // relative, in the second parameter
  bool detect = true;                // codimension-two points
  // Values of either parameter at which to report the curve's point (AUTO's UZ), exact (solved
  // with that parameter held), and, with `stop`, end the curve there (AUTO's UZSTOP).
  struct Value {
    bool second = true;  // of the second parameter, else the first
    double value = 0.0;
    bool stop = false;
  };
  std::vector<Value> user_values;

  OptionCheck validate() const;
};

struct EquilibriumCurvePoint {
  int index = 0;  // negative on the backward half
  double first = 0.0, second = 0.0;
  Eigen::VectorXd state;
  Eigen::VectorXcd eigenvalues;  // largest real part first
  // HB curve: omega^2 on the Hopf part, -k^2 on the neutral-saddle part (eigenvalues +-k); NaN
  // on an LP curve.
  double kappa = std::numeric_limits<double>::quiet_NaN();
  bool neutral_saddle = false;
  double lyapunov = std::numeric_limits<double>::quiet_NaN();  // l1, on the Hopf part
  double residual = 0.0;                                       // |f|_inf
  Eigen::VectorXd tangent;                                     // unit, scaled norm
  double step = 0.0;
  int iterations = 0;
  // The borders of the minimally augmented system at this point (its null vectors), and which
  // two entries of G a Hopf curve's system uses: values that travel with the points.
  Eigen::MatrixXd right, left;
  int entry_a = 0, entry_b = 3;
};

struct EquilibriumCurveEvent {
  std::string type;         // "BT", "CP", "GH", "ZH", "HH"; "UZ" a user value
  std::string description;  // for people
  double first = 0.0, second = 0.0;
  double uncertainty = 0.0;  // in the second parameter: the final bracket
  bool located = false;
  int after_point = 0;
  double arclength = 0.0;
  EquilibriumCurvePoint at;
  // Normal-form coefficients in MatCont's normalisation: BT's "a" and "b" (w0' = w1,
  // w1' = a w0^2 + b w0 w1; only sign(a b) does not depend on it), CP's "c" (w' = c w^3), GH's
  // "l2" (Re c2 / omega, in l1's units), ZH's "b", "c", "a", "s", "theta" and HH's "p11",
  // "p12", "p21", "p22", "theta", "delta" (codim2_coefficients.hpp).
  std::vector<std::pair<std::string, double>> coefficients;
  std::string note;
};

struct EquilibriumCurve {
  EquilibriumEventType kind = EquilibriumEventType::Fold;  // Fold or Hopf
  std::string first_name, second_name;
  int first = -1, second = -1;
  std::vector<std::string> state_names;
  std::vector<EquilibriumCurvePoint> points;
  std::vector<EquilibriumCurveEvent> events;
  StopReason stop = StopReason::ParameterBound;
  std::optional<StopReason> backward_stop;  // the backward half's
  std::string stop_reason;
  std::string origin;  // "HB at rho = 24.7368421053"
  ParameterValues start_values;
  EquilibriumCurveOptions options;
  double seconds = 0.0;
  bool started() const { return stop != StopReason::StartFailed; }
};

struct EquilibriumCurveCallbacks {
  std::function<void(const EquilibriumCurvePoint&)> on_point;
  std::function<void(const EquilibriumCurveEvent&)> on_event;
  std::function<bool()> stop_requested;
};

// The curve of `event` (an LP or HB of `branch`, a branch of equilibria of `system`) in the
// branch's parameter and `second`, both ways from the event within the options' windows. Throws
// std::invalid_argument for an event of another kind, a second parameter equal to the first, a
// window that does not hold the event, or options out of their domain.
EquilibriumCurve continue_equilibrium_curve(const OdeSystem& system,
                                            const EquilibriumBranch& branch,
                                            const EquilibriumEvent& event, int second,
                                            EquilibriumCurveOptions options,
                                            const EquilibriumCurveCallbacks& callbacks = {});

// A located codimension-two point of a curve of equilibria (its type and the curve's kind), at
// both its parameters' values.
struct CodimensionTwoPoint {
  std::string type;                                      // "BT", "CP", "ZH", "HH"
  EquilibriumEventType on = EquilibriumEventType::Fold;  // the curve it lies on
  int first = -1, second = -1;
  ParameterValues values;  // both parameters set
  Eigen::VectorXd state;
  double kappa = std::numeric_limits<double>::quiet_NaN();  // the Hopf curve's there
  // The largest |x|_inf and |kappa| along the curve it lies on: the new curve's arclength is
  // scaled by them at least (and the state by 1 at least).
  double state_scale = 0.0, kappa_scale = 0.0;
};

// The point of `event`, a located codimension-two point of `curve`.
CodimensionTwoPoint codimension_two_point(const OdeSystem& system, const EquilibriumCurve& curve,
                                          const EquilibriumCurveEvent& event);

// Which curve continue_from_codimension_two follows from `point` (the kind below) and its kappa
// there (omega^2 of the new Hopf curve's pair: 0 at BT; NaN for a fold curve). Throws
// std::invalid_argument as that function does.
struct CurveFromCodimensionTwo {
  EquilibriumEventType kind = EquilibriumEventType::Fold;
  double kappa = std::numeric_limits<double>::quiet_NaN();
};
CurveFromCodimensionTwo curve_from_codimension_two(const OdeSystem& system,
                                                   const CodimensionTwoPoint& point);

// The other curve through `point` in the same two parameters (AUTO's and MatCont's switches at
// codimension-two points): at BT the Hopf curve from a fold curve (from omega = 0: Hopf points
// one way, neutral saddles the other) or the fold curve from a Hopf curve; at ZH likewise (the
// Hopf curve of the pair beside the zero eigenvalue); at HH the Hopf curve of the other pair; at
// CP the fold curve through the cusp. Both ways from the point. Throws std::invalid_argument for
// another type, parameters that are not two different ones, a window that does not hold the
// point, or options out of their domain.
EquilibriumCurve continue_from_codimension_two(const OdeSystem& system,
                                               const CodimensionTwoPoint& point,
                                               EquilibriumCurveOptions options,
                                               const EquilibriumCurveCallbacks& callbacks = {});

}  // namespace sympathy
