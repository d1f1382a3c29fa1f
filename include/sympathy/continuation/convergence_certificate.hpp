// Whether a trajectory's fate is known: it has entered a stable periodic orbit's contracting
// neighbourhood and is converging to it at the orbit's rate. What lets a basin run stop long
// before its end (the paper's median time to synchronize at Table III is 7 s of a 100 s run).
//
// The trajectory's returns to a local Poincare section of the orbit, the hyperplane through its
// point z* normal to the flow there (in the scaled norm below), crossed in the flow's direction
// near z*: at each return z_k (cubic Hermite interpolation between two samples, with f at both:
// error about (omega dt)^4 / 384, 3e-7 relative at dt = 0.01 s and 1.7 Hz) the distance
// d_k = |D^-1 (z_k - z*)|_inf, D the orbit's amplitude per state (half its range over a period, at
// least 1e-3 of the largest). Certified at return k when
//   - the orbit is stable with a margin: its largest nontrivial |mu| (rho) is below 1 by more than
//     the margin and than ten times its trivial multiplier's error (the multipliers' error);
//   - the last `returns` + 1 returns lie within `radius` of z*, each after about one period
//     (within 5%: a return of another orbit that passes near z* is not this orbit's);
//   - d_k / d_(k-m) <= rho^(m/2) (m = `returns`): the distance has fallen at least at half the
//     leading multiplier's log-rate, as it does in the orbit's linear neighbourhood (asymptotically
//     at rho^m; the half leaves room for a complex pair's turning and for the other modes).
// Newton's convergence is no certificate (it converges to unstable orbits too), and an unstable
// orbit never certifies: a run lingering near one (the row setup's lower in-phase orbit at
// k = 60 N/m, largest multiplier 1.156, for about 20 s) is not stopped there.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

struct CertificateOptions {
  double radius = 0.05;  // of the neighbourhood, relative to the orbit's amplitude per state
  int returns = 4;       // returns over which the distance must fall
  double margin = 1e-3;  // 1 - rho must exceed it

  OptionCheck validate() const;
};

class ConvergenceCertificate {
 public:
  // `orbit`: converged, of `system` at its parameters. Integrates it once over its period (its
  // amplitudes). Throws std::invalid_argument for an orbit that did not converge or options out
  // of their domain.
  ConvergenceCertificate(const OdeSystem& system, const PeriodicOrbit& orbit,
                         CertificateOptions options = {});

  // Whether the orbit can certify at all (stable with the margin).
  bool eligible() const { return eligible_; }
  double rate() const { return rate_; }  // rho, the largest nontrivial |mu|

  // One sample (t, z) of a trajectory, times increasing; true once certified (and after).
  bool add(double t, const Eigen::VectorXd& z);
  bool certified() const { return certified_; }
  // The returns to the section so far: their times and distances.
  const std::vector<double>& return_times() const { return times_; }
  const std::vector<double>& distances() const { return distances_; }

 private:
  double side(const Eigen::VectorXd& z) const;  // <n, D^-1 (z - z*)>
  double distance(const Eigen::VectorXd& z) const;

  const OdeSystem& system_;
  CertificateOptions options_;
  ParameterValues parameters_;
  Eigen::VectorXd point_, scale_, normal_;  // z*, D, the section's normal in scaled coordinates
  double period_ = 0.0, rate_ = 1.0;
  bool eligible_ = false, certified_ = false;
  bool has_previous_ = false;
  double t_previous_ = 0.0, g_previous_ = 0.0;
  Eigen::VectorXd z_previous_;
  std::vector<double> times_, distances_;
};

}  // namespace sympathy
