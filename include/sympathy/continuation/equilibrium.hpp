// Equilibria of a system, f(x; p) = 0, and their stability: Newton on f at fixed parameter values,
// and the eigenvalues of df/dx there (sorted by real part, largest first).
//
// Newton's tolerance is relative to the state's size: a step below `tolerance` times
// max(1, |x|_inf) ends it, so that a system whose states are of order 100 converges as well as
// one of order 1 (an absolute residual bound refused such starts: AUTO-style demos with states
// near 100 stalled at |f| = 1e-8 with steps of 1e-14 relative).
#pragma once

#include <complex>
#include <optional>
#include <string>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy {

struct EquilibriumNewtonOptions {
  double tolerance = 1e-12;  // on the last step, relative to max(1, |x|_inf)
  int max_iterations = 12;
  OptionCheck validate() const;
};

// Eigenvalues of df/dx, largest real part first (ties: positive imaginary part first).
Eigen::VectorXcd sorted_eigenvalues(const Eigen::MatrixXd& jacobian);

// The one of `eigenvalues` nearest `target` (an eigenvalue followed from one point to the next).
std::complex<double> nearest_eigenvalue(const Eigen::VectorXcd& eigenvalues,
                                        std::complex<double> target);

// How many eigenvalues have a real part above `tolerance` times max(1, the largest |lambda|).
int unstable_count(const Eigen::VectorXcd& eigenvalues, double tolerance = 1e-9);

struct Equilibrium {
  bool converged = false;
  std::string reason;  // why not
  Eigen::VectorXd state;
  ParameterValues parameters;
  Eigen::VectorXcd eigenvalues;  // sorted_eigenvalues
  double residual = 0.0;         // |f|_inf at the state
  int iterations = 0;
  int unstable = 0;  // eigenvalues with positive real part
};

// Newton from `guess` at parameter values `p`. Does not throw on failure: `converged` says.
Equilibrium solve_equilibrium(const OdeSystem& system, const ParameterValues& p,
                              const Eigen::VectorXd& guess,
                              const EquilibriumNewtonOptions& options = {});

// A Hopf point: an equilibrium (state, at parameter values `values`) with a pair of eigenvalues
// +-i omega on the imaginary axis.
struct HopfPoint {
  double parameter = 0.0;  // the continued parameter's value
  ParameterValues values;
  Eigen::VectorXd state;
  double omega = 0.0;   // > 0
  double period = 0.0;  // 2 pi / omega: the period of the orbits born there
  // f_x q = i omega q, |q| = 1, Re q orthogonal to Im q and |Re q| >= |Im q|: the small orbits are
  // x + eps (Re q cos(omega t) - Im q sin(omega t)) to first order.
  Eigen::VectorXcd eigenvector;
  // The first Lyapunov coefficient (Kuznetsov's l1, in the normalization <p, q> = 1 with the
  // adjoint p): negative, supercritical (the small orbits are stable where the equilibrium is
  // not); positive, subcritical. From f's exact second and third derivatives (Taylor jets),
  // where the system has none by differences of the exact f_x (relative error about 1e-6);
  // nullopt where they are not finite.
  std::optional<double> lyapunov;
  // Kuznetsov's c1 in the same normalization (l1 = Re c1 / omega): its imaginary part is how the
  // frequency changes with the orbits' amplitude. nullopt where l1 is.
  std::optional<std::complex<double>> c1;
  double uncertainty = 0.0;  // in the parameter
};

// The Hopf data of the equilibrium `x` at `p` for its eigenvalue nearest i * omega_guess (the
// pair with the largest imaginary part if omega_guess <= 0): omega, the eigenvector, l1.
HopfPoint describe_hopf(const OdeSystem& system, const ParameterValues& p, const Eigen::VectorXd& x,
                        double omega_guess);

// "supercritical (l1 = -0.31)", "subcritical (l1 = 2.1)", "degenerate (l1 = 0)" (exactly zero:
// a piecewise-linear field's linear centre), "criticality unknown".
std::string describe_criticality(const std::optional<double>& lyapunov);

}  // namespace sympathy
