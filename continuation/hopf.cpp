#include "sympathy/continuation/hopf.hpp"

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

#include "sympathy/continuation/shooting.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy {

OptionCheck HopfStartOptions::validate() const {
  if (!non_negative(amplitude)) return OptionProblem{"amplitude", "a number >= 0 (0: automatic)"};
  if (max_iterations < 1 || max_iterations > 100)
    return OptionProblem{"max_iterations", "an integer from 1 to 100"};
  return std::nullopt;
}

std::optional<HopfPoint> hopf_point_near(const OdeSystem& system, int parameter,
                                         const ParameterValues& p, const Eigen::VectorXd& guess,
                                         double omega_guess, double step, std::string& why) {
  const double p0 = system.parameter(p, parameter);
  Equilibrium e0 = solve_equilibrium(system, p, guess);
  if (!e0.converged) {
    why = "no equilibrium near the orbit: " + e0.reason;
    return std::nullopt;
  }
  std::complex<double> l0 = nearest_eigenvalue(e0.eigenvalues, {0.0, omega_guess});
  if (std::abs(l0.imag() - omega_guess) > 0.2 * omega_guess) {
    why = "the equilibrium near the orbit has no pair of eigenvalues near +-i " +
          format_double(omega_guess) + " (nearest " + format_double(l0.real()) + " + " +
          format_double(l0.imag()) + "i)";
    return std::nullopt;
  }
  double pa = p0, ga = l0.real();
  double pb = p0 + step;
  Eigen::VectorXd x = e0.state;
  std::complex<double> followed = l0;
  for (int k = 0; k < 40; ++k) {
    const Equilibrium e = solve_equilibrium(system, system.with_parameter(p, parameter, pb), x);
    if (!e.converged) {
      why = "the equilibrium could not be followed to " + format_double(pb) + ": " + e.reason;
      return std::nullopt;
    }
    x = e.state;
    followed = nearest_eigenvalue(e.eigenvalues, followed);
    const double gb = followed.real();
    const double scale = std::max(std::abs(pb), std::abs(step));
    if (gb == ga || std::abs(pb - pa) <= 1e-13 * scale || gb == 0.0) {
      HopfPoint h = describe_hopf(system, e.parameters, e.state, followed.imag());
      h.parameter = pb;
      h.uncertainty = std::abs(pb - pa);
      return h;
    }
    const double next = pb - gb * (pb - pa) / (gb - ga);
    pa = pb;
    ga = gb;
    pb = next;
    if (!std::isfinite(pb)) break;
  }
  why = "the real part of the pair was not driven to zero in 40 secant steps";
  return std::nullopt;
}

std::optional<HopfExpansion> hopf_expansion(const OdeSystem& system, int parameter,
                                            const HopfPoint& hopf) {
  if (!hopf.lyapunov || *hopf.lyapunov == 0.0) return std::nullopt;
  const double h = 1e-6 * std::max(1.0, std::abs(hopf.parameter));
  std::complex<double> pair[2];
  for (int k = 0; k < 2; ++k) {
    const double p = hopf.parameter + (k ? h : -h);
    const Equilibrium e =
        solve_equilibrium(system, system.with_parameter(hopf.values, parameter, p), hopf.state);
    if (!e.converged) return std::nullopt;
    pair[k] = nearest_eigenvalue(e.eigenvalues, {0.0, hopf.omega});
  }
  const std::complex<double> slope = (pair[1] - pair[0]) / (2 * h);  // mu' + i omega'
  if (!(std::isfinite(slope.real()) && std::isfinite(slope.imag()) && slope.real() != 0.0))
    return std::nullopt;
  const double re_c1 = hopf.omega * *hopf.lyapunov;
  HopfExpansion x;
  x.offset = -re_c1 / (4 * slope.real());
  // Without c1's imaginary part (a Hopf point read from an older JSON), the period at 2 pi / omega.
  if (hopf.c1) x.frequency = (hopf.c1->imag() - slope.imag() * re_c1 / slope.real()) / 4;
  if (!(std::isfinite(x.offset) && std::isfinite(x.frequency))) return std::nullopt;
  return x;
}

namespace {

// The first orbit's amplitude along Re q (state units): the option's, else 2% of the state's size.
double start_amplitude(const HopfPoint& hopf, const HopfStartOptions& start) {
  return start.amplitude > 0.0 ? start.amplitude
                               : 0.02 * std::max(1.0, hopf.state.lpNorm<Eigen::Infinity>());
}

// Newton on the orbit of amplitude `amplitude` along Re q (see orbit_from_hopf), from the
// normal form's parameter and period at that amplitude (`expansion`: hopf_expansion, computed
// once per start). With `growth`, also the family's direction there (shooting unknowns and
// parameter) in which the amplitude grows: d(x, p)/d eps from the same bordered system, its last
// row's right-hand side |Re q|^2.
PeriodicOrbit orbit_at_amplitude(const OdeSystem& system, int parameter, const HopfPoint& hopf,
                                 const OrbitOptions& options, const HopfStartOptions& start,
                                 const std::optional<HopfExpansion>& expansion, double amplitude,
                                 Eigen::VectorXd* growth = nullptr) {
  const Eigen::VectorXd qr = hopf.eigenvector.real(), qi = hopf.eigenvector.imag();
  const double eps = amplitude / qr.lpNorm<Eigen::Infinity>();
  ShootingProblem problem(system, options.shooting);
  const int n = system.dimension();
  const int N = problem.unknowns();
  const Eigen::VectorXd z_ref = hopf.state + eps * qr;
  const PhaseSection section{z_ref, qi};
  // Newton starts at the normal form's parameter and period (to second order in eps), not at p_H
  // and 2 pi / omega, where the bordered Jacobian has the family's double multiplier 1 nearly in
  // it.
  double p = hopf.parameter, period = hopf.period;
  if (expansion) {
    p += expansion->offset * eps * eps;
    // The frequency's correction only where it is a correction: an amplitude so large that it
    // halves the frequency (or turns it negative) is past where a second-order term says anything.
    const double frequency = hopf.omega + expansion->frequency * eps * eps;
    if (frequency > 0.5 * hopf.omega) period = 2 * std::numbers::pi / frequency;
  }
  ParameterValues values = hopf.values;
  Eigen::VectorXd x = problem.unknowns_from(z_ref, values, period);
  const double tolerance =
      attainable_tolerance(options.newton.residual_tolerance, options.newton.rtol_factor,
                           options.shooting.flow, hopf.state.lpNorm<Eigen::Infinity>());
  double residual = 0.0;
  bool converged = false;
  const auto bordered = [&](const ShootingProblem::Evaluation& e) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(N + 1, N + 1);
    m.topRows(N) = Eigen::MatrixXd(problem.jacobian(e, true));
    m.row(N).head(n) = qr.transpose();
    return m;
  };
  for (int it = 0; it < start.max_iterations; ++it) {
    values = system.with_parameter(hopf.values, parameter, p);
    const auto e = problem.evaluate(x, values, section, true, parameter);
    Eigen::VectorXd g(N + 1);
    g.head(N) = e.residual;
    g[N] = qr.dot(x.head(n) - hopf.state) - eps * qr.squaredNorm();
    residual = g.lpNorm<Eigen::Infinity>();
    if (!g.allFinite()) break;
    if (residual <= tolerance) {
      converged = true;
      if (growth) {
        Eigen::VectorXd along = Eigen::VectorXd::Zero(N + 1);
        along[N] = qr.squaredNorm();
        *growth = bordered(e).fullPivLu().solve(along);
      }
      break;
    }
    const Eigen::VectorXd dy = bordered(e).fullPivLu().solve(-g);
    x += dy.head(N);
    p += dy[N];
  }
  if (!converged)
    throw std::runtime_error("no orbit near the Hopf point at " +
                             system.parameter_names()[parameter] + " = " +
                             format_double(hopf.parameter) + " with amplitude " +
                             format_double(eps * qr.lpNorm<Eigen::Infinity>()) + " (residual " +
                             format_double(residual) + ")");
  PeriodicOrbit orbit =
      solve_periodic_orbit(system, values, x.head(n), problem.period(x), {}, options);
  if (!orbit.converged())
    throw std::runtime_error("the orbit near the Hopf point does not converge at fixed " +
                             system.parameter_names()[parameter] + " = " + format_double(p) + ": " +
                             orbit.newton.reason);
  return orbit;
}

// orbit_from_hopf, with the amplitude of the orbit found in `used`.
PeriodicOrbit first_orbit(const OdeSystem& system, int parameter, const HopfPoint& hopf,
                          const OrbitOptions& options, const HopfStartOptions& start,
                          const std::optional<HopfExpansion>& expansion, double& used,
                          Eigen::VectorXd* growth = nullptr) {
  if (auto wrong = start.validate()) throw std::invalid_argument("Hopf start: " + wrong->message());
  if (!(hopf.omega > 0.0) || hopf.eigenvector.size() != system.dimension())
    throw std::invalid_argument("Hopf start: the Hopf point has no frequency or eigenvector");
  // Retried at a quarter and a sixteenth of the amplitude: 2% of the state's size is too large
  // where the Hopf point is slow and strongly attracting (issue 33: AUTO's c2c, omega 0.09,
  // l1 = -8.8, whose state's size 8.5 asked for an orbit of amplitude 0.17).
  const double first = start_amplitude(hopf, start);
  std::string failures;
  for (double amplitude : {first, first / 4, first / 16}) {
    PeriodicOrbit orbit;
    try {
      orbit =
          orbit_at_amplitude(system, parameter, hopf, options, start, expansion, amplitude, growth);
      used = amplitude;
    } catch (const std::runtime_error& e) {
      failures += (failures.empty() ? "" : "; ") + std::string(e.what());
      continue;
    }
    // Where the family is nearly vertical (|l1| tiny), the small orbit's radial multiplier lies
    // within the rank tolerance of 1 (1 - 1.3e-7 at AUTO's chu, l1 = -2.5e-4, amplitude 0.03),
    // and a branch started there takes itself for a continuum of orbits: one multiplier set
    // aside as structural at every point after, the others wrong (chu: a trusted PD at
    // alpha = 7.566 that a simulation and AUTO (8.196) deny). An automatic amplitude grows (x4,
    // x16: the multiplier's distance from 1 grows as its square) until the orbit is isolated.
    for (double larger : {4 * amplitude, 16 * amplitude}) {
      if (orbit.family_dimension == 0 || start.amplitude > 0.0) break;
      try {
        Eigen::VectorXd wider_growth;
        PeriodicOrbit wider = orbit_at_amplitude(system, parameter, hopf, options, start, expansion,
                                                 larger, &wider_growth);
        orbit = std::move(wider);
        used = larger;
        if (growth) *growth = std::move(wider_growth);
      } catch (const std::runtime_error&) {
        break;  // the smaller one, as it is
      }
    }
    return orbit;
  }
  throw std::runtime_error(failures);
}

}  // namespace

PeriodicOrbit orbit_from_hopf(const OdeSystem& system, int parameter, const HopfPoint& hopf,
                              const OrbitOptions& options, const HopfStartOptions& start) {
  double used = 0.0;
  return first_orbit(system, parameter, hopf, options, start,
                     hopf_expansion(system, parameter, hopf), used);
}

Branch continue_from_hopf(const OdeSystem& system, int parameter, const HopfPoint& hopf,
                          const ContinuationOptions& options,
                          const ContinuationCallbacks& callbacks, const HopfStartOptions& start) {
  // The family goes the way its amplitude grows: d(x, p)/d eps at the first orbit orients the
  // first tangent. By the sign of p - p_H alone, a family whose parameter barely moves (issue 33:
  // AUTO's chu, l1 = -2.5e-4, the first orbit 2e-6 off the Hopf point) was sent back into the
  // Hopf point and ended there after one point.
  double amplitude = 0.0;
  Eigen::VectorXd growth;
  const auto expansion = hopf_expansion(system, parameter, hopf);
  PeriodicOrbit orbit =
      first_orbit(system, parameter, hopf, options.orbit, start, expansion, amplitude, &growth);
  double p = system.parameter(orbit.parameters, parameter);
  // A user point between the Hopf point and the first orbit would never be passed (issue 33:
  // AUTO's lrz asks for rho = 24.7263, 0.01 from its Hopf point, where the first orbit lay 0.1
  // off): the first orbit is taken closer, at the amplitude (p - p_H growing as its square) that
  // puts it halfway between the Hopf point and the nearest such value, where it is still
  // isolated.
  double nearest = 1.0;  // of |u - p_H| / |p - p_H|
  for (double u : options.user_points)
    if ((u - hopf.parameter) * (p - u) > 0.0)
      nearest = std::min(nearest, std::abs(u - hopf.parameter) / std::abs(p - hopf.parameter));
  if (nearest < 1.0) {
    const double closer = amplitude * std::sqrt(0.5 * nearest);
    try {
      Eigen::VectorXd inner_growth;
      PeriodicOrbit inner = orbit_at_amplitude(system, parameter, hopf, options.orbit, start,
                                               expansion, closer, &inner_growth);
      if (inner.family_dimension == 0) {
        orbit = std::move(inner);
        growth = std::move(inner_growth);
        p = system.parameter(orbit.parameters, parameter);
      }
    } catch (const std::runtime_error&) {
      // the first orbit as it was
    }
  }
  if (!growth.allFinite()) growth.resize(0);  // then the side of the Hopf point the orbit is on
  Continuation continuation(system, parameter, options);
  Branch branch = continuation.run(orbit, p >= hopf.parameter ? 1 : -1, callbacks, growth);
  branch.origin =
      "HB at " + system.parameter_names()[parameter] + " = " + format_double(hopf.parameter);
  return branch;
}

}  // namespace sympathy
