#include "sympathy/core/stiffness.hpp"

#include <cmath>
#include <ctime>
#include <sstream>
#include <stdexcept>

#include <Eigen/Eigenvalues>

namespace sympathy {

double spectral_radius(const Eigen::MatrixXd& a) {
  if (a.rows() != a.cols()) throw std::invalid_argument("spectral_radius: a square matrix");
  if (a.size() == 0) return 0.0;
  const Eigen::EigenSolver<Eigen::MatrixXd> eigen(a, /*computeEigenvectors=*/false);
  return eigen.eigenvalues().cwiseAbs().maxCoeff();
}

// The threshold (kStiffIndicator = 1.4), measured (2026-11-24, `sympathy orbit cases/row2.toml
// --start in-phase --set k=K --set c=C`: the indicator and steps as the default preset measures
// them; CPU s of the whole orbit computation, transient, Newton and multipliers, with `--method
// adams` and with `--method bdf --sensitivities forward`):
//
//   k (N/m)  c (N s/m)  indicator  Adams steps  BDF steps  h rho   Adams (s)  BDF (s)
//   14.7     0.0185     0.52         841        1625       0.032   0.17       0.46
//   1e5      50         0.80        1585        1973       0.44    0.25       0.64
//   1e4      500        1.07        1707        1593       0.88    0.21       0.28
//   1e5      500        1.04        1695        1631       1.1     0.20       0.32
//   1e6      500        1.36        2316        1697       1.1     0.28       0.42
//   1e7      1000       1.59        4789        3016       1.0     1.08       0.63
//   1e6      2000       2.6         4158        1602       1.5     8.94       0.33
//   1e6      5000       9.2        15218        1651       0.72    6.26       0.35
//
// (indicators uncapped; measured from the converged orbit; near the threshold the point of the
// transient it is measured at moves it by about 10%: 1.50 for the k = 1e7 orbit from the search's
// first period, where either choice is within a factor of two of the other.)
// The runs with sensitivities suffer more than the plain period shows (at 2.6 the plain Adams run
// takes 2.6 times BDF's steps, the whole computation 27 times BDF's time). The fast preset
// (Dormand-Prince at rtol 1e-8) crosses at the same place: faster at 1.04 (k = 1e7, c = 1000:
// 0.36 s against 0.55 s), slower at 1.78 (k = 1e6, c = 2000: 0.34 s against 0.25 s).
StiffnessEstimate measure_stiffness(const OdeSystem& system, const FlowOptions& nonstiff,
                                    const Eigen::VectorXd& z0, const ParameterValues& p, double t0,
                                    double period, int samples) {
  if (!(period > 0.0) || samples < 1)
    throw std::invalid_argument("measure_stiffness: a positive period and at least one sample");
  const std::clock_t begin = std::clock();
  StiffnessEstimate e;
  FlowOptions bdf = nonstiff;
  bdf.method = Method::BDF;
  bdf.nonlinear_solver = NonlinearSolver::Newton;
  Flow stiff(system, bdf);
  stiff.advance(z0, p, t0, t0 + period);
  e.bdf_steps = std::max(1L, stiff.statistics().steps);
  // The non-stiff run stops at kMeasuredUpTo times BDF's steps: beyond, it is stiff whatever the
  // rest would show, and a non-stiff method on a stiff period is what costs (the k = 1e6, c = 5000
  // orbit: 35 000 Adams steps for the whole period, a third of the orbit's time).
  FlowOptions capped = nonstiff;
  capped.max_steps =
      std::min(nonstiff.max_steps,
               static_cast<long>(std::ceil(kMeasuredUpTo * static_cast<double>(e.bdf_steps))));
  Flow flow(system, capped);
  int next = 0;  // the next sample time: t0 + (next + 1/2) period / samples
  try {
    flow.advance_observing_steps(
        z0, p, t0, t0 + period, [&](double t_old, double t_new, const Eigen::VectorXd& z) {
          bool sampled = false;
          for (; next < samples && t0 + (next + 0.5) * period / samples <= t_new; ++next)
            sampled = true;
          if (!sampled) return;
          const double rho = spectral_radius(system.jacobian(t_new, z, p));
          e.rate = std::max(e.rate, rho);
          e.largest_h_rate = std::max(e.largest_h_rate, (t_new - t_old) * rho);
        });
  } catch (const IntegrationError&) {
    // A failure of its own (a step size underflow), or the caller's step limit: not the cap.
    if (flow.statistics().steps + 1 < capped.max_steps || capped.max_steps == nonstiff.max_steps)
      throw;
    e.capped = true;
  }
  e.steps = flow.statistics().steps;
  e.indicator = static_cast<double>(e.steps) / static_cast<double>(e.bdf_steps);
  e.seconds = static_cast<double>(std::clock() - begin) / CLOCKS_PER_SEC;
  return e;
}

FlowOptions after_stiffness(const FlowOptions& options, const StiffnessEstimate& estimate,
                            double threshold) {
  if (estimate.indicator <= threshold || options.method == Method::BDF) return options;
  FlowOptions stiff = options;
  stiff.method = Method::BDF;
  stiff.nonlinear_solver = NonlinearSolver::Newton;
  stiff.sensitivities = Sensitivities::ForwardModule;
  return stiff;
}

std::string stiffness_note(const StiffnessEstimate& estimate, double threshold) {
  std::ostringstream s;
  s.precision(2);
  s << "stiffness indicator " << (estimate.capped ? "at least " : "") << estimate.indicator
    << " (BDF above " << threshold << ")";
  return s.str();
}

}  // namespace sympathy
