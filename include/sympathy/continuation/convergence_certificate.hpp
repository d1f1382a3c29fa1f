// Whether a trajectory's fate is known: it has entered a stable periodic orbit's contracting
// neighbourhood and is converging to it at the orbit's rate. What lets a basin run stop long
// before its end (the paper's median time to synchronize at Table III is 7 s of a 100 s run).
//
// The trajectory's returns to a local Poincare section of the orbit, the hyperplane through its
// point z* normal to the flow there (in the scaled coordinates below), crossed in the flow's
// direction near z*: each return z_k by cubic Hermite interpolation between two samples with f at
// both (error about (omega dt)^4 / 384: 3e-7 relative at dt = 0.01 s and 1.7 Hz). Its deviation
// e_k = z_k - z* is measured in the monodromy matrix's eigenvectors (each of unit length in the
// scaled norm, D the orbit's amplitude per state: half its range over a period, at least 1e-3 of
// the largest): e_k = sum c_i v_i, and d_k = max |c_i| over the nontrivial ones (the trivial
// one, along f, is a shift in phase, which the section takes out). In the orbit's linear
// neighbourhood each c_i is multiplied by mu_i at every return, so d_(k+1) <= rho d_k, rho the
// largest nontrivial |mu|, however the modes turn (a distance in the states themselves rose and
// fell by 5x from one return to the next on the row setup's anti-phase orbit, whose slowest pair
// turns). Certified at return k when
//   - the orbit is stable with a margin: rho is below 1 by more than the margin and than ten
//     times its trivial multiplier's error (the multipliers' error);
//   - the last `returns` + 1 returns lie within `radius` of z*, each one period after the last
//     (within 5%: another orbit that passes near z* is not this one);
//   - each of those returns fell from the one before by a factor of at most rho + slack (1 - rho)
//     (at least at half the linear neighbourhood's rate by default: the slack for the neglected
//     O(d^2) terms; the row setup's anti-phase orbit at k = 60 N/m, rho = 0.985, fell by 0.985
//     per return from d = 0.3 on).
// Newton's convergence is no certificate (it converges to unstable orbits too), and an unstable
// orbit never certifies: a run lingering near one (the row setup's lower in-phase orbit at
// k = 60 N/m, largest multiplier 1.156, for about 20 s) is not stopped there.
#pragma once

#include <complex>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

struct CertificateOptions {
  double radius = 0.25;  // of the neighbourhood, in the eigen-coordinates of the scaled norm
  int returns = 4;       // returns that must each fall at the orbit's rate
  double slack = 0.5;    // a return may fall by rho + slack (1 - rho): at half the rate
  double margin = 1e-3;  // 1 - rho must exceed it

  OptionCheck validate() const;
};

// What a certificate needs of an orbit, computed once: its point, scales and section, its
// monodromy's eigenvectors and amplitudes (one integration with sensitivities over the period).
// Shared by the certificates of every trajectory tested against the orbit.
struct OrbitNeighbourhood {
  // `orbit`: converged, of `system` at its parameters. Throws std::invalid_argument for an orbit
  // that did not converge or options out of their domain.
  OrbitNeighbourhood(const OdeSystem& system, const PeriodicOrbit& orbit,
                     CertificateOptions options = {});

  CertificateOptions options;
  ParameterValues parameters;
  Eigen::VectorXd point, scale, normal;  // z*, D, the section's normal in scaled coordinates
  double period = 0.0;
  double rate = 1.0;      // rho, the largest nontrivial |mu|
  bool eligible = false;  // stable with the margin: the orbit can certify
  // Rows of V^-1 (V: the eigenvectors of D^-1 M D, unit inf-norm) for the nontrivial
  // multipliers, c = coordinates * D^-1 e, and those columns of V.
  Eigen::MatrixXcd coordinates, modes;
  Eigen::VectorXcd multipliers;  // the nontrivial ones, in the order of coordinates' rows
};

class ConvergenceCertificate {
 public:
  // `system`: the orbit's (its f at the samples); one per trajectory. `reach`: how near z* (in the
  // scaled inf-norm) a crossing of the section counts as a return; 0.5 (half the orbit's
  // amplitude) is well beyond the certificate's radius and short of the orbit's other side; a
  // torus around the orbit is followed further out (attractor_run.cpp).
  ConvergenceCertificate(const OdeSystem& system,
                         std::shared_ptr<const OrbitNeighbourhood> neighbourhood,
                         double reach = 0.5);

  bool eligible() const { return orbit_->eligible; }
  double rate() const { return orbit_->rate; }

  // One sample (t, z) of a trajectory, times increasing; true once certified (and after).
  bool add(double t, const Eigen::VectorXd& z);
  bool certified() const { return certified_; }
  // At the last return, sum |c_i| max_j |v_i[j]| over `components` (empty: all, |v_i| = 1): in
  // the linear neighbourhood the deviation's scaled inf-norm in those states at every later
  // return stays below it (each |c_i| only shrinks). Infinity before the first return.
  double bound(const std::vector<int>& components = {}) const;
  // The returns to the section so far: their times and distances d_k.
  const std::vector<double>& return_times() const { return times_; }
  const std::vector<double>& distances() const { return distances_; }
  // The eigen-coordinates c of the deviation at the last return (empty before the first).
  const Eigen::VectorXcd& last_coordinates() const { return last_; }

 private:
  double side(const Eigen::VectorXd& z) const;  // <n, D^-1 (z - z*)>
  double near(const Eigen::VectorXd& z) const;  // |D^-1 (z - z*)|_inf

  const OdeSystem& system_;
  std::shared_ptr<const OrbitNeighbourhood> orbit_;
  double reach_ = 0.5;
  bool certified_ = false;
  Eigen::VectorXcd last_;  // c at the last return
  bool has_previous_ = false;
  double t_previous_ = 0.0, g_previous_ = 0.0;
  Eigen::VectorXd z_previous_;
  std::vector<double> times_, distances_;
};

// The same for a stable equilibrium x*: with A = f_x(x*), every eigenvalue's real part below 0
// (alpha, the largest, below -margin times the largest |lambda|), the deviation e = x - x* in A's
// eigenvectors (each of unit length; not where they are nearly dependent, condition above 1e8),
// c = V^-1 e, has |c|^2 falling along the linear flow at least at the rate 2 alpha. The field
// itself says how fast it falls at a sample: (|c|^2)' / (2 |c|^2) = Re(c^H V^-1 f(x)) / |c|^2.
// Certified once, over consecutive samples each within `radius` of x* (in the eigen-coordinates,
// relative to max(1, |x*|_inf)) and each falling at least at (1 - slack) alpha (half the linear
// rate by default: the slack for the nonlinear terms), |c| has fallen by a factor e: the linear
// decay dominates there, and the run converges to x*. A run that passes near an unstable
// equilibrium never certifies (no eligible certificate), nor one near x* that does not fall.
class RestCertificate {
 public:
  RestCertificate(const OdeSystem& system, const ParameterValues& p, const Eigen::VectorXd& rest,
                  CertificateOptions options = {});
  bool eligible() const { return eligible_; }
  double rate() const { return alpha_; }
  // One sample of a trajectory, in time order; true once certified (and after).
  bool add(const Eigen::VectorXd& z);

 private:
  const OdeSystem& system_;
  ParameterValues p_;
  Eigen::VectorXd rest_;
  CertificateOptions options_;
  Eigen::MatrixXcd coordinates_;  // V^-1
  double alpha_ = 0.0, scale_ = 1.0;
  bool eligible_ = false, certified_ = false;
  double streak_start_ = std::numeric_limits<double>::quiet_NaN();  // |c|^2 where it began
  Eigen::VectorXd f_;
};

}  // namespace sympathy
