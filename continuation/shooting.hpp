// The periodic-orbit problem by single or multiple shooting.
//
// Unknowns x = [z_0, ..., z_{m-1}, T] for an autonomous system; the period is fixed (and not an
// unknown) for a periodically forced one. Residual
//   r_j = Phi(z_j over T/m) - z_{j+1}   (j = 0..m-1, z_m = z_0),
//   r_p = <f(z_ref), z_0 - z_ref>       (phase condition, autonomous only: a Poincare section
//                                       through a reference point, across the flow there).
// The Jacobian is block sparse: the segments' transition matrices on the block diagonal, -I on
// the block superdiagonal (cyclically), f at the segment ends / m in the period column, f(z_ref)
// in the phase row. Derivatives come from the flow's forward sensitivities.
#pragma once

#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "core/flow.hpp"
#include "core/ode_system.hpp"

namespace sympathy {

struct ShootingOptions {
  int segments = 1;
  FlowOptions flow;
};

class ShootingProblem {
 public:
  // `forced_period`: the period of a non-autonomous system (ignored for autonomous ones).
  ShootingProblem(const OdeSystem& system, ShootingOptions options, double forced_period = 0.0);

  int segments() const { return options_.segments; }
  int dimension() const { return n_; }
  int unknowns() const { return n_ * options_.segments + (autonomous_ ? 1 : 0); }
  bool autonomous() const { return autonomous_; }
  const OdeSystem& system() const { return system_; }

  // The phase condition's section: through z_ref, normal f(z_ref).
  void set_phase_reference(const Eigen::VectorXd& z_ref);
  const Eigen::VectorXd& phase_reference() const { return z_ref_; }
  const Eigen::VectorXd& phase_normal() const { return f_ref_; }

  // Unknowns from an initial state and period: the segment states by integrating one period.
  Eigen::VectorXd unknowns_from(const Eigen::VectorXd& z0, double period);
  double period(const Eigen::VectorXd& x) const;
  Eigen::VectorXd state(const Eigen::VectorXd& x, int segment = 0) const {
    return x.segment(segment * n_, n_);
  }

  struct Evaluation {
    Eigen::VectorXd residual;
    bool derivatives = false;
    std::vector<Eigen::MatrixXd> transitions;  // per segment, dPhi/dz_j
    std::vector<Eigen::VectorXd> end_rates;    // per segment, f at its end
    Eigen::MatrixXd parameter_sensitivities;   // n x m: dPhi/dp per segment (if asked)
    int parameter = -1;
  };
  // Residual, and with `derivatives` the transition matrices (and dPhi/dp for `parameter`).
  // Throws IntegrationError if a segment cannot be integrated.
  Evaluation evaluate(const Eigen::VectorXd& x, bool derivatives, int parameter = -1);

  // d(residual)/dx as a sparse matrix, rows = unknowns(); with `parameter_column` the column
  // d(residual)/dp appended (the evaluation must carry it).
  Eigen::SparseMatrix<double> jacobian(const Evaluation& e, bool parameter_column = false) const;

  const Flow& flow() const { return flow_; }
  Flow& flow() { return flow_; }

 private:
  const OdeSystem& system_;
  ShootingOptions options_;
  int n_;
  bool autonomous_;
  double forced_period_;
  Flow flow_;
  Eigen::VectorXd z_ref_, f_ref_;
};

}  // namespace sympathy
