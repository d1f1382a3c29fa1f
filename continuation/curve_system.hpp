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

  const OdeSystem& system() const { return system_; }
  const CurveOptions& options() const { return options_; }
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

  // The whole turns each angle state gains over a period (ShootingProblem's winding), from the
  // orbit at z0 with `period` at the values p: a rotating orbit's residual is
  // Phi_T(z0) - 2 pi k - z0. Integrates one period where the system has angle states.
  void wind_as(const Eigen::VectorXd& z0, double period, const ParameterValues& p) {
    problem_.unknowns_from(z0, p, period);
  }
  // The scaled norm's weights from the start u (state by its largest component, the period by
  // itself, each parameter by its window's width).
  void set_scales(const Eigen::VectorXd& u);
  // The phase section through the orbit at u; the borders to the null vectors at e.
  void set_section(const Eigen::VectorXd& u);
  // The integration's noise, measured on the start's evaluation e (u its unknowns): how far the
  // monodromy misses mapping the flow's direction at z0 onto the one at the period's end, which
  // it does exactly for the true solution, |M f(z0) - f(z(T))| / |f(z0)|. The corrector's
  // difference step, its tolerances and every point's uncertainty floor were set for a
  // monodromy error of about 1e-9 (the default preset's) and hold up to 1e-8; above that they
  // grow with this noise (its ratio to 1e-8; the difference step as its square root). Fixed, at
  // the fast preset's looser tolerances (noise 2e-8 to 4e-6 at rtol 2e-8 to 3e-7) they asked the
  // chord to contract below its noise, and its stalled steps were reported as divergence: the
  // anti-phase BP curve in (k, c) ended early at rtol 3e-8 and did not start at 5e-8.
  void measure_noise(const Eigen::VectorXd& u, const Evaluation& e);
  double noise() const { return noise_; }
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
  double noise_ = 0.0;      // measure_noise; 0 until measured (the constants as set)
  double tolerance_ = 0.0;  // of the shooting residual: the attainable one (set_scales)
  // The constants' factor for the noise: max(1, noise_ / 1e-8).
  double noise_factor() const;
};

}  // namespace sympathy::detail
