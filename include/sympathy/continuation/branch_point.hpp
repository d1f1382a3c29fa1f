// A simple branch point of cycles (and of equilibria) located on a regular system instead of by its
// crossing multiplier alone.
//
// Why: at a branch point the shooting Jacobian [F_x F_p] loses rank, so the branch's points near
// it are corrected only to the residual over a vanishing singular value. Where the branch is not
// held in a symmetric subspace (a transcritical crossing of two families), the corrected orbits
// drift off the branch across it: on AUTO's lcbp the orbit corrected at the crossing lies
// 8.7e-9 inside the circle r = 2, and the multiplier crossing put the branch point at
// p1 = 1.99999998204 (exact: 2) while its bracket claimed 1.0e-8.
//
// Moore's system in y = (x, p) (the shooting unknowns and the parameter), psi and beta,
//   F(y) + beta psi = 0,   F_y(y)^T psi = 0,   psi^T psi = 1,
// 2N + 2 equations in 2N + 2 unknowns (N = the shooting residual's size), is regular at a simple
// branch point (two branches crossing transversally: a transcritical crossing or a pitchfork),
// with beta = 0 and psi the left null vector of F_y there. Newton on it finds the point to the
// integration's accuracy. Its second derivatives d(F_y^T psi)/dy come from forward differences
// of Jacobians (CVODES has no second-order forward sensitivities): one evaluation with
// derivatives per unknown and Newton step, so the solver is for small shooting problems.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "sympathy/continuation/branch_space.hpp"
#include "sympathy/continuation/shooting.hpp"

namespace sympathy {

struct BranchPointOptions {
  int max_iterations = 8;
  // Converged: the Newton step in y below this in the branch's scaled norm, or, after two
  // steps, below a hundred times this (the integration's noise: the monodromy's error of about
  // 1e-10 limits y to about that). With second derivatives good to about 1e-5 the steps
  // contract by about that much: 1e-3, 1e-8, 1e-13 from a guess 1e-3 off.
  double step_tolerance = 1e-11;
  // Above this many unknowns (N + 1) the differences cost too much (one monodromy each per
  // step): the crossing's location stands.
  int max_unknowns = 41;
};

struct BranchPointSolution {
  bool converged = false;
  std::string reason;                      // why not
  Eigen::VectorXd y;                       // (unknowns, parameter) at the branch point
  ShootingProblem::Evaluation evaluation;  // at y, with derivatives and the parameter's column
  double residual = 0.0;                   // |F(y)|_inf
  double beta = 0.0;
  // How far the true branch point's parameter may lie from y's: the last Newton step plus the
  // first-order effect of the errors of F (`residual_noise`, or |F| at the solution if larger)
  // and of F_y (`monodromy_noise`), in each entry with the worst signs, through the inverse of
  // the system's Jacobian.
  double uncertainty = 0.0;
  int iterations = 0;
  int evaluations = 0;
};

// Moore's system for any F(y) = 0 of N equations in y (N + 1 unknowns): what the cycles' and the
// equilibria's branch points are located on. `linearize` gives F and F_y = [F_x F_p] at y; the
// second derivatives are its forward differences along each unknown (kDifferenceStep in the
// scaled norm, whose `weights` are y's). `residual_noise` and `jacobian_noise` are the errors of F
// and of F_y's entries, for the uncertainty.
struct MooreLinearization {
  bool ok = false;
  std::string failure;       // why not
  Eigen::VectorXd residual;  // F(y)
  Eigen::MatrixXd jacobian;  // N x (N + 1): [F_x F_p]
};
using MooreLinearize = std::function<MooreLinearization(const Eigen::VectorXd& y)>;

struct MooreSolution {
  bool converged = false;
  std::string reason;        // why not
  Eigen::VectorXd y;         // at the branch point
  Eigen::VectorXd psi;       // F_y's left null vector there, |psi| = 1
  Eigen::MatrixXd jacobian;  // F_y at y
  double residual = 0.0;     // |F(y)|_inf
  double beta = 0.0;
  double uncertainty = 0.0;  // of y's parameter (as BranchPointSolution's)
  int iterations = 0;
  int evaluations = 0;
};
MooreSolution solve_moore(const MooreLinearize& linearize, const Eigen::VectorXd& weights,
                          const Eigen::VectorXd& guess, double residual_noise,
                          double jacobian_noise, const BranchPointOptions& options = {});

// The Hessian of psi^T F at y applied to `direction` (unscaled): (F_y(y + h d)^T psi - gradient)
// / h, `gradient` being F_y(y)^T psi; one linearization. What the regular system's second
// derivatives and switching's branching equation are made of. nullopt, with `failure`, where
// y + h d cannot be linearized.
std::optional<Eigen::VectorXd> hessian_along(const MooreLinearize& linearize,
                                             const Eigen::VectorXd& y, const Eigen::VectorXd& psi,
                                             const Eigen::VectorXd& gradient,
                                             const Eigen::VectorXd& direction, double h,
                                             std::string& failure);

// The tangent of the other branch through a simple branch point: the root of the algebraic
// branching equation sum_ij c_ij t_i t_j = 0 on `kernel`'s two columns (c_ij = psi^T
// F_yy[phi_i, phi_j], in the kernel's coordinates) least parallel to `old` (unit; all in one
// scaled norm). Throws std::runtime_error where the equation has no two real roots (not a simple
// branch point).
Eigen::VectorXd branching_tangent(const Eigen::Matrix2d& c, const Eigen::MatrixXd& kernel,
                                  const Eigen::VectorXd& old);

// F = the shooting residual of `problem` in the phase condition's `section`, for the continued
// `parameter` (`space` gives the parameter values): its linearization for the functions above.
MooreLinearize shooting_linearization(ShootingProblem& problem, const PhaseSection& section,
                                      const BranchSpace& space, int parameter);

// Newton on Moore's system from `guess` (unknowns, parameter), for the continued `parameter`,
// in the phase condition's `section`; `space` gives the parameter values and the scaled norm.
BranchPointSolution solve_branch_point(ShootingProblem& problem, const PhaseSection& section,
                                       const BranchSpace& space, int parameter,
                                       const Eigen::VectorXd& guess, double residual_noise,
                                       double monodromy_noise,
                                       const BranchPointOptions& options = {});

}  // namespace sympathy
