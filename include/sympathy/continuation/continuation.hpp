// Pseudo-arclength continuation of periodic orbits in one parameter.
//
// Unknowns Y = (x, p): the shooting unknowns and the parameter. A point satisfies the shooting
// equations F(x, p) = 0 (phase condition on a section through an earlier point) and the
// arclength condition <tau, Y - Y_prev> = ds in a scaled norm (each state component by the
// largest amplitude met on the branch so far, the period by itself, the parameter by the range
// asked for), so that steps mean the same in metres, radians and newtons per metre. The tangent at
// a converged point comes from that point's own Jacobian: nothing is integrated twice.
//
// Steps grow after easy corrections and shrink after hard or failed ones, after a step that
// turns the tangent too far, and when a multiplier near the unit circle moves more than a set
// amount, so that a narrow window of instability is not stepped over. Between points, test
// functions (the tangent's parameter component for folds, |mu| - 1 of each multiplier crossing the
// unit circle) locate every bifurcation to a relative tolerance in the parameter.
//
// A periodically forced (non-autonomous) system is continued with its period fixed at the
// start's (the forcing's; the continued parameter must not change it): the unknowns are then the
// segment states alone, there is no phase condition and no trivial multiplier, and no shift in
// time leaves an orbit alone. Branch switching and two-parameter curves are for autonomous
// systems only.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/branch_space.hpp"
#include "sympathy/continuation/corrector.hpp"
#include "sympathy/continuation/detection.hpp"
#include "sympathy/continuation/grazing.hpp"

namespace sympathy {

struct SwitchStart;  // branch_switching.hpp

struct ContinuationCallbacks {
  std::function<void(const ContinuationPoint&)> on_point;  // each point as it is accepted
  std::function<void(const Bifurcation&)> on_event;        // each bifurcation as it is located
  std::function<bool()> stop_requested;                    // polled between points
};

class Continuation {
 public:
  // `parameter`: index of the named parameter of `system` that the runs vary. The system is only
  // read: parameter values travel with the orbits and points, so one system serves many runs.
  Continuation(const OdeSystem& system, int parameter, ContinuationOptions options);

  // Continues from `start` (an orbit, at its own parameter values; the other parameters keep
  // them along the branch) in the direction of increasing (+1) or decreasing (-1) parameter.
  // When `initial_tangent` is given (branch switching), it orients the first tangent instead.
  Branch run(const PeriodicOrbit& start, int direction, const ContinuationCallbacks& callbacks = {},
             const Eigen::VectorXd& initial_tangent = Eigen::VectorXd());

  // Branch switching (branch_switching.cpp, used by switch_branch): from `base`, an orbit at a
  // branch point (of period 2T at a period doubling), along the direction in the null space of
  // [F_x F_p] there nearest to `critical` (unknowns and parameter, unscaled), orthogonal to
  // `old_tangent` (or, if that is empty, with no parameter component); one step corrected each
  // way, and the branch continued away from the event from each. `start` receives the direction
  // and the checks of the first steps. `mirror` (if not empty): a symmetry of f that maps one
  // half of the new branch onto the other, which is then reflected rather than computed.
  // `transcritical`: the new direction is instead the root of the algebraic branching equation
  // least parallel to `old_tangent` (branching_direction): where two families cross at an angle
  // (a BP that breaks no symmetry) the new branch is not orthogonal to the old one.
  Branch run_switched(const PeriodicOrbit& base, const Eigen::VectorXd& critical,
                      const Eigen::VectorXd& old_tangent, const ContinuationCallbacks& callbacks,
                      SwitchStart& start, const Eigen::MatrixXd& mirror = Eigen::MatrixXd(),
                      bool transcritical = false);

  const ContinuationOptions& options() const { return options_; }

 private:
  // One run as the driver's problem (continuation.cpp, driver.hpp).
  class Run;
  friend class Run;
  // The run's pieces, each in its own file: BranchSpace (scaled norm, tangents), correct
  // (corrector.hpp), predict (predictor.hpp), track (multiplier_tracking.hpp), detect
  // (detection.hpp), locate (location.hpp), step control (step_control.hpp).
  // run(), with the state scales widened to at least `sizes` (if not empty).
  Branch run_from(const PeriodicOrbit& start, int direction, const ContinuationCallbacks& callbacks,
                  const Eigen::VectorXd& initial_tangent, const Eigen::VectorXd& sizes);
  // The corrector's residual tolerance: the options', or what the integration attains at the
  // branch's state scale if that is larger (attainable_tolerance).
  double corrector_tolerance() const;
  // In `section` (the point from's); `expected`: the guess's residual expected
  // (CorrectorOptions::expected_residual).
  Correction correct_step(const PhaseSection& section, const Eigen::VectorXd& from,
                          const Eigen::VectorXd& tangent, double step, const Eigen::VectorXd& guess,
                          const Eigen::SparseMatrix<double>* chord, double expected = 0.0) const;
  ContinuationPoint make_point(const Correction& c, const Eigen::VectorXd& tangent, int index,
                               double step) const;
  // The point at arclength s from a along a's tangent, in a's section: what location probes. With
  // the step's end b and its Jacobian (in a's section), the guess comes from the cubic through a
  // and b (predict_between) and the quasi-Newton steps from the Jacobian interpolated between
  // a's and b's; from a's tangent and a's Jacobian otherwise.
  std::optional<ContinuationPoint> point_at(
      const ContinuationPoint& a, double s, std::string& why, const ContinuationPoint* b = nullptr,
      const Eigen::SparseMatrix<double>* jacobian_b = nullptr) const;
  // The branch's point at the parameter value `bound`, between a and b (b beyond it), in a's
  // section; nullopt when it cannot be corrected.
  std::optional<ContinuationPoint> point_on_bound(const ContinuationPoint& a,
                                                  const ContinuationPoint& b, double bound) const;
  // The same where the unknown y_k (k = unknowns(): the parameter; unknowns() - 1: the period of
  // an autonomous system) takes `value`, between a and b.
  std::optional<ContinuationPoint> point_where(const ContinuationPoint& a,
                                               const ContinuationPoint& b, int k,
                                               double value) const;
  // The options' user points the step from a to b passed (b at one, or a and b on either side),
  // each as a UserPoint event: the branch's point at the value (point_on_bound), ordered along
  // the step (user_points.cpp).
  TrustLimit trust_limit() const {
    return {options_.trust_limit, options_.orbit.shooting.flow.rtol};
  }
  std::vector<Bifurcation> user_points_between(const ContinuationPoint& a,
                                               const ContinuationPoint& b) const;
  // The options' user values (UserValue) the step from a to b passed, each as a UserPoint event
  // (user_points.cpp): a period by point_where, a state's extreme on the one locator from probes
  // along a's tangent (b's Jacobian, in a's section, for their chord); each with whether the
  // branch stops there (UserValue::stop).
  std::vector<std::pair<Bifurcation, bool>> user_values_between(
      const ContinuationPoint& a, const ContinuationPoint& b,
      const Eigen::SparseMatrix<double>* jacobian_b) const;
  // A user value's quantity at a point (its samples, or one plain period).
  double quantity(const UserValue& v, const ContinuationPoint& p) const;

  // A hybrid system's orbit's crossings of its switching surfaces in one period (empty for a
  // smooth system), and where they change between a (at_a) and b (at_b): bisection along the
  // step, each probe corrected as location's are (grazing.cpp).
  std::vector<int> crossings_of(const ContinuationPoint& p) const;
  CrossingChange crossing_change(const ContinuationPoint& a, const ContinuationPoint& b,
                                 const std::vector<int>& at_a, const std::vector<int>& at_b,
                                 const Eigen::SparseMatrix<double>* jacobian_b) const;

  // The new branch's unit tangent (scaled) at a branch point y0 with Jacobian [F_x F_p],
  // left null vector psi and kernel (two orthonormal columns, scaled), all in `section`: the root
  // of the algebraic branching equation least parallel to `old` (unit, scaled). Throws
  // std::runtime_error where the equation has no two real roots (branch_switching.cpp).
  Eigen::VectorXd branching_direction(const PhaseSection& section, const Eigen::VectorXd& y0,
                                      const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& psi,
                                      const Eigen::MatrixXd& kernel,
                                      const Eigen::VectorXd& old) const;

  // A branch point located by its crossing, moved to the solution of the regular branch-point
  // system (branch_point.hpp) where the crossing alone is not regular: a crossing of one
  // multiplier that keeps the subspace (or none declared), on a branch of isolated orbits. The
  // solution must lie between a and b; otherwise the event stays as located, with a note.
  void refine_branch_point(Bifurcation& e, const ContinuationPoint& a,
                           const ContinuationPoint& b) const;

  // The Hopf point where a branch that turned back at `turn` (no multiplier at +1) ends, if its
  // orbits shrank into an equilibrium there (hopf.hpp); nullopt otherwise.
  std::optional<HopfPoint> hopf_end(const Bifurcation& turn) const;

  // At the start of each run: the options as asked (requested_), the stiffness at the start
  // measured where options_.orbit.switch_when_stiff asks for it (the start's own measurement
  // where it carries one) and BDF chosen where it is stiff, the shooting problem made for the run.
  // The choice is the run's, recorded in its branch (options, stiffness).
  void begin_run(const PeriodicOrbit& start);

  const OdeSystem& system_;
  int parameter_;
  ContinuationOptions requested_;               // as constructed (the defaults filled in)
  ContinuationOptions options_;                 // this run's: requested_ with its integrator chosen
  std::optional<StiffnessEstimate> stiffness_;  // where this run measured it
  std::unique_ptr<ShootingProblem> problem_;
  std::unique_ptr<BranchSpace> space_;  // made for each run, from its start
  InvariantSubspace subspace_;          // the start's: every point's multipliers labelled by it
  int family_dimension_ = 0;
  // The shooting Jacobian (with its parameter column) at the last accepted point, in its section:
  // the chord steps' matrix for the next step and for locating events after it.
  Eigen::SparseMatrix<double> chord_jacobian_;
  Eigen::SparseMatrix<double> jacobian_before_;  // the same at the point before it
  // The last step's prediction was on the branch as it stood (no chord step, no iteration): the
  // next corrections start with the integration with sensitivities (derivatives_first).
  bool predictions_land_ = false;
  double guess_residual_ = 0.0;  // of the last step's guess, where it was computed
};

}  // namespace sympathy
