// The minimally augmented system of a two-parameter bifurcation curve (bifurcation_curve.hpp):
// its unknowns U = (y, T, p1, p2), its residual G(U) (shooting, phase, test function), its
// Jacobian (exact shooting columns from the flow's sensitivities, the rest by forward
// differences of monodromies), the unit tangent and a chord corrector. Internal to the
// continuation layer: the curve run (bifurcation_curve.cpp) is its only user.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/curve_test_function.hpp"
#include "sympathy/continuation/shooting.hpp"

namespace sympathy::detail {

// Where the critical multipliers live: the monodromy's block inside the orbit's subspace or
// across it, or (LP) the shooting Jacobian in the subspace.
enum class CriticalBlock { Inside, Across, Shooting };

class CurveSystem {
 public:
  CurveSystem(const OdeSystem& system, BifurcationType kind, const InvariantSubspace& subspace,
              CriticalBlock block, int first, int second, ParameterValues base,
              const CurveOptions& options);

  int unknowns() const { return m_ + 3; }  // N: G has N - 1 entries
  int first_index() const { return m_ + 1; }
  int second_index() const { return m_ + 2; }
  ParameterValues values(const Eigen::VectorXd& u) const;
  Eigen::VectorXd state(const Eigen::VectorXd& u) const { return v_ * u.head(m_); }
  Eigen::VectorXd unknowns_of(const Eigen::VectorXd& z0, double period, double p1, double p2) const;

  // One integration with the monodromy; the rest is linear algebra on it.
  struct Evaluation {
    bool ok = false;
    std::string failure;
    Eigen::VectorXd end;        // Phi_T(z0)
    Eigen::MatrixXd monodromy;  // whole state
    Eigen::VectorXd end_rate;   // f(Phi_T(z0))
    Eigen::VectorXd residual;   // G: shooting (m), phase, test function
    BorderedSingularity::Value test;
  };
  Evaluation evaluate(const Eigen::VectorXd& u);
  // G again from an evaluation's monodromy, under the current phase section and borders.
  void assemble(const Eigen::VectorXd& u, Evaluation& e) const;
  double shooting_residual(const Evaluation& e) const {
    return e.residual.head(m_).cwiseAbs().maxCoeff();
  }

  // The (N - 1) x N Jacobian at u (e: its evaluation); nullopt if a difference failed.
  std::optional<Eigen::MatrixXd> jacobian(const Eigen::VectorXd& u, const Evaluation& e);
  // The unit tangent (scaled norm) from a Jacobian, oriented along `previous` (or, if empty,
  // with the second parameter growing in `direction`).
  Eigen::VectorXd tangent(const Eigen::MatrixXd& jacobian, const Eigen::VectorXd& previous,
                          int direction = +1) const;
  double dot(const Eigen::VectorXd& a, const Eigen::VectorXd& b) const;
  double norm(const Eigen::VectorXd& a) const { return std::sqrt(dot(a, a)); }
  double weight(int unknown) const { return weights_[unknown]; }  // of the scaled norm

  // Chord Newton from `guess` with `jacobian`, under one more condition: the arclength
  // <tau, U - from> = ds (tau given), or U[index] = value (index >= 0).
  struct Correction {
    bool converged = false;
    std::string reason;
    Eigen::VectorXd u;
    Evaluation evaluation;
    int iterations = 0;
  };
  struct Condition {
    Eigen::VectorXd tangent, from;
    double step = 0.0;
    int index = -1;
    double value = 0.0;
  };
  Correction correct(Eigen::VectorXd guess, const Condition& condition,
                     const Eigen::MatrixXd& jacobian);

  // The scaled norm's weights from the start u (state by its largest component, the period by
  // itself, each parameter by its window's width).
  void set_scales(const Eigen::VectorXd& u);
  // The phase section through the orbit at u; the borders to the null vectors at e.
  void set_section(const Eigen::VectorXd& u);
  void update_borders(const Evaluation& e);
  // The borders as they are, and back to saved ones (a second half of a curve starts from the
  // borders its start was corrected with, not those the first half ended with).
  const BorderedSingularity& borders() const { return *borders_; }
  void set_borders(const BorderedSingularity& b) { borders_ = b; }

  // The point at u (converged: e), with its multipliers and critical ones.
  CurvePoint point(const Eigen::VectorXd& u, const Evaluation& e, const Eigen::MatrixXd& jacobian,
                   const Eigen::VectorXd& tangent) const;
  // The multipliers of the whole monodromy other than the trivial and the critical ones: their
  // indices in p.floquet.multipliers, and their values.
  std::vector<int> other_indices(const CurvePoint& p) const;
  std::vector<std::complex<double>> others(const CurvePoint& p) const;

  FlowStatistics statistics() const { return problem_.statistics(); }
  int evaluations() const { return evaluations_; }
  const InvariantSubspace& subspace() const { return subspace_; }

 private:
  Eigen::MatrixXd critical_matrix(const Evaluation& e) const;
  Eigen::MatrixXd block(const Evaluation& e) const;
  std::vector<std::complex<double>> critical_multipliers(const Evaluation& e, bool* neutral) const;

  const OdeSystem& system_;
  BifurcationType kind_;
  InvariantSubspace subspace_;
  CriticalBlock block_;
  int first_, second_;
  ParameterValues base_;
  CurveOptions options_;
  ShootingProblem problem_;
  int n_, m_;
  Eigen::MatrixXd v_, c_;      // orthonormal bases inside and across the subspace
  Eigen::VectorXd weights_;    // of U: 1 / typical size
  Eigen::VectorXd y_section_;  // the phase section: through y_section_, normal normal_
  Eigen::VectorXd normal_;
  std::optional<BorderedSingularity> borders_;
  int evaluations_ = 0;
};

}  // namespace sympathy::detail
