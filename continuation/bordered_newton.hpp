// One Newton step on a system G(y) = 0 bordered by one linear condition row^T y = value: what
// the pseudo-arclength correctors with exact Jacobians (equilibria, curves of equilibria) take
// at each iterate. Internal to the continuation layer.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Dense>

namespace sympathy::detail {

// The step dy solving [J; row^T] dy = -[g; r] (g = G(y), r = row^T y - value), or nullopt with
// the reason: the residual or the step not finite, the bordered matrix singular (`what` names the
// system in the reason).
inline std::optional<Eigen::VectorXd> bordered_newton_step(const Eigen::MatrixXd& jacobian,
                                                           const Eigen::VectorXd& row,
                                                           const Eigen::VectorXd& g, double r,
                                                           const std::string& what,
                                                           std::string& why) {
  const Eigen::Index m = jacobian.rows();
  Eigen::VectorXd rhs(m + 1);
  rhs << g, r;
  if (!rhs.allFinite()) {
    why = "the " + what + " is not finite at a Newton iterate";
    return std::nullopt;
  }
  Eigen::MatrixXd a(m + 1, jacobian.cols());
  a.topRows(m) = jacobian;
  a.row(m) = row.transpose();
  const Eigen::FullPivLU<Eigen::MatrixXd> lu(a);
  if (!lu.isInvertible()) {
    why = "the bordered Jacobian of the " + what + " is singular";
    return std::nullopt;
  }
  Eigen::VectorXd dy = lu.solve(-rhs);
  if (!dy.allFinite()) {
    why = "a Newton step is not finite";
    return std::nullopt;
  }
  return dy;
}

}  // namespace sympathy::detail
