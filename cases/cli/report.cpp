#include "cases/cli/report.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cases/cli/common.hpp"

namespace sympathy::cli {

OrbitReport describe_orbit(const MetronomeModel& model, const PeriodicOrbit& orbit) {
  OrbitReport r;
  const int positions = model.dimension() / 2;
  const int pendula = model.metronome_count();
  r.amplitudes.assign(positions, 0.0);
  r.phase_differences.assign(pendula - 1, std::nan(""));
  if (!(orbit.period > 0.0)) return r;
  FlowOptions o;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  Flow flow(model, o);
  const int samples = 800;
  std::vector<double> times;
  for (int k = 0; k <= samples; ++k) times.push_back(orbit.period * k / samples);
  Eigen::VectorXd lo = orbit.state0, hi = orbit.state0, previous = orbit.state0;
  std::vector<double> crossing(pendula, std::nan(""));
  double t_previous = 0.0;
  try {
    flow.sample(orbit.state0, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
      lo = lo.cwiseMin(z);
      hi = hi.cwiseMax(z);
      for (int i = 0; i < pendula; ++i) {
        const int c = model.angle_index(i);
        if (t > 0.0 && previous[c] < 0.0 && z[c] >= 0.0 && std::isnan(crossing[i]))
          crossing[i] = t_previous + (t - t_previous) * (-previous[c]) / (z[c] - previous[c]);
      }
      previous = z;
      t_previous = t;
    });
  } catch (const IntegrationError&) {
    return r;  // amplitudes unknown; the orbit's own figures still stand
  }
  for (int i = 0; i < positions; ++i) r.amplitudes[i] = 0.5 * (hi[i] - lo[i]);
  for (int i = 1; i < pendula; ++i) {
    if (std::isnan(crossing[0]) || std::isnan(crossing[i])) continue;
    double phase = 2.0 * std::numbers::pi * (crossing[0] - crossing[i]) / orbit.period;
    phase = std::remainder(phase, 2.0 * std::numbers::pi);
    if (phase <= -std::numbers::pi) phase += 2.0 * std::numbers::pi;
    r.phase_differences[i - 1] = phase;
  }
  return r;
}

void print_orbit(std::FILE* out, const MetronomeModel& model, const PeriodicOrbit& orbit,
                 const OrbitReport& report, const OrbitOptions& options) {
  const auto names = model.state_names();
  const auto& f = orbit.floquet;
  std::fprintf(out, "  period       %.12g s    frequency %.9g Hz\n", orbit.period,
               1.0 / orbit.period);
  std::fprintf(out, "  amplitudes  ");
  for (std::size_t i = 0; i < report.amplitudes.size(); ++i)
    std::fprintf(out, " %s %.6g", names[i].c_str(), report.amplitudes[i]);
  if (!report.phase_differences.empty()) {
    std::fprintf(out, "\n  phases to th1");
    for (std::size_t i = 0; i < report.phase_differences.size(); ++i)
      std::fprintf(out, " th%zu %+.6f", i + 2, report.phase_differences[i]);
  }
  std::fprintf(out, "\n  multipliers  (modulus, argument in rad)\n");
  for (const auto& m : f.multipliers) {
    std::fprintf(out, "    %.12f  %+.6f", m.modulus(), std::arg(m.value));
    if (m.trivial) std::fprintf(out, "   trivial");
    if (m.structural) std::fprintf(out, "   structural");
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "  stability    %s", to_string(f.stability).c_str());
  if (f.unstable_count > 0)
    std::fprintf(out, " (%d multiplier%s outside the unit circle)", f.unstable_count,
                 f.unstable_count > 1 ? "s" : "");
  std::fprintf(out, "; largest other |mu| = %.9f, tolerance %g\n", f.max_modulus,
               options.floquet.stability_tolerance);
  std::fprintf(out, "  accuracy     Newton residual %.2e; trivial multiplier |mu - 1| = %.2e\n",
               orbit.residual, f.trivial_error);
  if (orbit.family_dimension > 0)
    std::fprintf(
        out,
        "  not isolated the shooting Jacobian has a %d-dimensional null space (a family of "
        "orbits, or a direction neutral to first order): %d structural multiplier%s at "
        "1, left out of the verdict\n",
        orbit.family_dimension, f.structural, f.structural > 1 ? "s" : "");
  const auto& s = orbit.newton;
  std::fprintf(out, "  newton       %s after %d iteration%s (%s); residuals",
               s.converged ? "converged" : "FAILED", s.iterations, s.iterations == 1 ? "" : "s",
               s.reason.c_str());
  for (double r : s.residual_norms) std::fprintf(out, " %.1e", r);
  std::fprintf(out, "\n");
  const auto& st = orbit.flow;
  const auto& flow = options.shooting.flow;
  const std::string solver =
      flow.nonlinear_solver == NonlinearSolver::Newton
          ? " (" + to_string(resolved_linear_solver(model, flow)) + " linear solver)"
          : "";
  std::fprintf(
      out,
      "  work         %d segment%s, %s%s rtol %g: %ld integrations, %ld steps, %ld rhs and "
      "%ld sensitivity-rhs evaluations, %ld Jacobians\n",
      orbit.segments, orbit.segments > 1 ? "s" : "", to_string(flow.method).c_str(), solver.c_str(),
      flow.rtol, st.calls, st.steps, st.rhs_evaluations, st.variational_evaluations,
      st.jacobian_evaluations);
}

void print_flow_statistics(std::FILE* out, const FlowStatistics& s) {
  std::fprintf(out,
               "  integration  %ld integrations, %ld steps, %ld error-test failures, %ld "
               "nonlinear iterations\n"
               "               %ld rhs and %ld sensitivity-rhs evaluations, %ld Jacobians, %ld "
               "linear-solver setups\n"
               "               %ld steep-zone band changes, %ld restarts at switching surfaces\n",
               s.calls, s.steps, s.error_test_failures, s.nonlinear_iterations, s.rhs_evaluations,
               s.variational_evaluations, s.jacobian_evaluations, s.linear_setups, s.steep_roots,
               s.switchings);
}

nlohmann::json multipliers_json(const FloquetAnalysis& floquet) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& m : floquet.multipliers) j.push_back({m.value.real(), m.value.imag()});
  return j;
}

nlohmann::json parameters_json(const OdeSystem& system) {
  nlohmann::json j = nlohmann::json::object();
  const auto names = system.parameter_names();
  for (int i = 0; i < static_cast<int>(names.size()); ++i) j[names[i]] = system.parameter(i);
  return j;
}

nlohmann::json orbit_json(const MetronomeModel& model, const PeriodicOrbit& orbit,
                          const OrbitReport& report) {
  const OdeSystem& system = model;
  const auto& f = orbit.floquet;
  nlohmann::json j;
  j["converged"] = orbit.converged();
  j["period"] = orbit.period;
  j["frequency"] = 1.0 / orbit.period;
  j["multipliers"] = multipliers_json(f);
  nlohmann::json moduli = nlohmann::json::array(), kinds = nlohmann::json::array();
  for (const auto& m : f.multipliers) {
    moduli.push_back(m.modulus());
    kinds.push_back(m.trivial ? "trivial" : m.structural ? "structural" : "");
  }
  j["moduli"] = moduli;
  j["multiplier_kinds"] = kinds;
  j["stable"] = f.stability == Stability::Stable;
  j["stability"] = to_string(f.stability);
  j["trivial_multiplier_error"] = f.trivial_error;
  j["residual"] = orbit.residual;
  j["family_dimension"] = orbit.family_dimension;
  j["segments"] = orbit.segments;
  j["state0"] = std::vector<double>(orbit.state0.data(), orbit.state0.data() + orbit.state0.size());
  j["state_names"] = system.state_names();
  nlohmann::json amplitudes = nlohmann::json::object();
  const auto names = system.state_names();
  for (std::size_t i = 0; i < report.amplitudes.size(); ++i)
    amplitudes[names[i]] = report.amplitudes[i];
  j["amplitudes"] = amplitudes;
  j["phase_differences"] = report.phase_differences;
  j["params"] = parameters_json(system);
  j["newton"] = {{"converged", orbit.newton.converged},
                 {"reason", orbit.newton.reason},
                 {"iterations", orbit.newton.iterations},
                 {"residual_norms", orbit.newton.residual_norms}};
  return j;
}

}  // namespace sympathy::cli
