// The space a branch lives in, shared by every piece of a continuation run (predictor, corrector,
// tangent, location): unknowns Y = (x, p), the shooting unknowns and the continued parameter; the
// parameter values at each p (the start's values with one entry varied); the scaled norm (each
// state component by the largest amplitude met on the branch so far, the period by itself, the
// parameter by the range asked for, so that steps mean the same in metres, radians and newtons
// per metre); the bordered linear system and the unit tangent; and the directions that do not
// change the orbit (shifts in time along it), which comparisons of tangents leave out (none for
// a periodically forced system, whose unknowns are the segment states alone, the period fixed).
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "sympathy/continuation/shooting.hpp"
#include "sympathy/core/linear_solve.hpp"

namespace sympathy {

class BranchSpace {
 public:
  // `base`: the start's parameter values; `parameter`: the continued one; `range`: the width of
  // the parameter interval (the parameter's scale); `rank_tolerance`: of the bordered solves.
  BranchSpace(const OdeSystem& system, const ShootingProblem& problem, int parameter,
              ParameterValues base, double range, double rank_tolerance);

  int unknowns() const { return unknowns_; }  // N: Y has N + 1 entries
  ParameterValues values_at(double v) const;

  // Resets the state scales to the orbit (z0, T) and sets the period's and parameter's weights.
  void reset_scales(const Eigen::VectorXd& z0, double period, const FlowOptions& flow,
                    const PeriodSamples* samples = nullptr);
  // Widens the state scales to the largest |z_i| on the orbit (z0, T) at parameter values p
  // (at T k / 100, k = 0 .. 100): scales only grow, so that a component whose amplitude grows
  // along the branch (a platform starting to swing) does not take all the arclength. The states
  // at those times are read off `samples` where they are the orbit's (every eighth), else a run
  // of `flow` samples them.
  void widen_scales(const Eigen::VectorXd& z0, const ParameterValues& p, double period,
                    const FlowOptions& flow, const PeriodSamples* samples = nullptr);

  // Widens the state scales to at least `size` (per state component): a switched branch's new
  // direction, which the orbit it starts from does not show.
  void include_sizes(const Eigen::VectorXd& size);
  const Eigen::VectorXd& sizes() const { return sizes_; }

  double dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const;
  const Eigen::VectorXd& weights() const { return weights_; }
  // The row <tau, .> of the arclength condition in the scaled norm.
  Eigen::VectorXd arclength_row(const Eigen::VectorXd& tangent) const;

  // The phase section through z normal to the flow there (parameter value v) in the scaled norm:
  // it contains the directions in which the orbit's amplitude changes.
  PhaseSection section(const Eigen::VectorXd& z, double v) const;
  // Cosine between two tangents with shifts in time along the orbits at `at` left out (how a
  // tangent is oriented).
  double orbit_cosine(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                      const Eigen::VectorXd& at) const;
  // The same in the orbit's own unknowns, the first segment's start, the period and the
  // parameter (how far a step turned the branch): the later segments' starts left out.
  double turn_cosine(const Eigen::VectorXd& u, const Eigen::VectorXd& v,
                     const Eigen::VectorXd& at) const;
  // The unit tangent from a shooting Jacobian with its parameter column, in the problem's current
  // phase section, oriented along `previous`.
  Eigen::VectorXd tangent(const Eigen::SparseMatrix<double>& jacobian, const Eigen::VectorXd& y,
                          const Eigen::VectorXd& previous) const;
  // The options of every solve of the bordered system.
  const LinearSolveOptions& linear() const { return linear_; }

 private:
  Eigen::VectorXd time_shift(const Eigen::VectorXd& y) const;

  const OdeSystem& system_;
  int parameter_;
  ParameterValues base_;
  double range_;
  int n_, m_, unknowns_;
  LinearSolveOptions linear_;
  Eigen::VectorXd weights_;  // of (unknowns, parameter): 1 / typical size
  Eigen::VectorXd sizes_;    // largest |z_i| met on the branch's orbits so far
};

// The shooting Jacobian (with its parameter column) bordered by one more row.
Eigen::SparseMatrix<double> bordered(const Eigen::SparseMatrix<double>& jacobian,
                                     const Eigen::VectorXd& row);

}  // namespace sympathy
