#include "cases/bench/bench_orbit.hpp"

#include "cases/cli/common.hpp"
#include "sympathy/core/assignment.hpp"

namespace sympathy::bench {

Setting setting(const std::string& name, Method method, double rtol, int segments,
                LinearSolver solver, Derivatives derivatives, bool resolve) {
  Setting s;
  s.name = name;
  s.flow.method = method;
  s.flow.nonlinear_solver =
      method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
  s.flow.rtol = rtol;
  s.flow.atol = rtol * 1e-2;
  s.flow.linear_solver = solver;
  s.flow.derivatives = derivatives;
  s.flow.resolve_steep_zones = resolve;
  s.segments = segments;
  return s;
}

Setting reference_setting() {
  return setting("reference", Method::BDF, 1e-13);
}

Setting check_setting() {
  return setting("check", Method::BDF, 1e-12);
}

OrbitOptions orbit_options(const Setting& s) {
  OrbitOptions o;
  o.shooting.flow = s.flow;
  o.shooting.segments = s.segments;
  // Newton cannot get below the integration's own error: the library asks for no less than
  // 20 rtol (NewtonOptions::rtol_factor), and at the tightest settings for 1e-10.
  o.newton.residual_tolerance = 1e-10;
  return o;
}

namespace {

std::vector<std::complex<double>> nontrivial_values(const FloquetAnalysis& f) {
  std::vector<std::complex<double>> v;
  for (const auto& m : f.multipliers)
    if (!m.trivial) v.push_back(m.value);
  return v;
}

}  // namespace

double multiplier_error(const std::vector<std::complex<double>>& a,
                        const std::vector<std::complex<double>>& b) {
  if (a.size() != b.size()) return INFINITY;
  const int n = static_cast<int>(a.size());
  Eigen::MatrixXd cost(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) cost(i, j) = std::norm(a[i] - b[j]);
  const std::vector<int> column = least_cost_assignment(cost);
  double worst = 0.0;
  for (int i = 0; i < n; ++i) worst = std::max(worst, std::abs(a[i] - b[column[i]]));
  return worst;
}

PeriodicOrbit orbit_guess(const MetronomeModel& model, const CaseFile& file, const StartSpec& start,
                          const InvariantSubspace& subspace) {
  PeriodicOrbit guess = find_periodic_orbit(model, model.default_parameters(),
                                            file.initial_state(&start), subspace, OrbitOptions{});
  guess.state0 = subspace.project(guess.state0 * (1.0 + 1e-3));
  guess.period *= 1.0 + 1e-3;
  return guess;
}

Result solve_orbit(const MetronomeModel& model, const PeriodicOrbit& guess,
                   const InvariantSubspace& subspace, const Setting& s) {
  Result r;
  const Stopwatch clock;
  try {
    const auto orbit = solve_periodic_orbit(model, guess.parameters, guess.state0, guess.period,
                                            subspace, orbit_options(s));
    r.converged = orbit.converged();
    r.period = orbit.period;
    r.state0 = orbit.state0;
    r.multipliers = nontrivial_values(orbit.floquet);
    r.trivial_error = orbit.floquet.trivial_error;
    r.flow = orbit.flow;
    r.iterations = orbit.newton.iterations;
    if (!r.converged) r.note = orbit.newton.reason;
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  r.seconds = clock.seconds();
  return r;
}

std::vector<std::string> bench_csv_columns() {
  return {"problem",
          "setting",
          "rtol",
          "period_error",
          "multiplier_error",
          "parameter_error",
          "trivial_multiplier_error",
          "seconds",
          "rhs_evaluations",
          "sensitivity_rhs_evaluations",
          "jacobians",
          "newton_iterations",
          "converged",
          "note",
          "steps",
          "points",
          "cpu_seconds",
          "seconds_per_period",
          "steps_per_period"};
}

std::vector<std::string> orbit_csv_row(const std::string& problem, const Setting& s,
                                       const Result& r, double period_error, double mu_error,
                                       double k_error, double seconds_per_period,
                                       double steps_per_period) {
  using cli::table_number;
  return {problem,
          s.name,
          table_number(s.flow.rtol, "%.0e"),
          table_number(period_error, "%.2e"),
          table_number(mu_error, "%.2e"),
          table_number(k_error, "%.2e"),
          table_number(r.trivial_error, "%.2e"),
          table_number(r.seconds, "%.4f"),
          std::to_string(r.flow.rhs_evaluations),
          std::to_string(r.flow.variational_evaluations),
          std::to_string(r.flow.jacobian_evaluations),
          std::to_string(r.iterations),
          r.converged ? "yes" : "no",
          r.note,
          std::to_string(r.flow.steps),
          "",
          "",
          std::isnan(seconds_per_period) ? "" : table_number(seconds_per_period, "%.6f"),
          std::isnan(steps_per_period) ? "" : table_number(steps_per_period, "%.0f")};
}

}  // namespace sympathy::bench
