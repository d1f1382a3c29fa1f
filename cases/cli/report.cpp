#include "cases/cli/report.hpp"

#include <algorithm>
#include <cmath>

namespace sympathy::cli {

OrbitReport describe_orbit(const OdeSystem& system, const PeriodicOrbit& orbit) {
  OrbitReport r;
  const int positions = system.dimension() / 2;
  r.amplitudes.assign(positions, 0.0);
  if (!(orbit.period > 0.0)) return r;
  FlowOptions o;
  o.rtol = 1e-9;
  o.atol = 1e-12;
  Flow flow(system, o);
  std::vector<double> times;
  for (int k = 0; k <= 400; ++k) times.push_back(orbit.period * k / 400.0);
  Eigen::VectorXd lo = orbit.state0, hi = orbit.state0;
  try {
    flow.sample(orbit.state0, 0.0, times, [&](double, const Eigen::VectorXd& z) {
      lo = lo.cwiseMin(z);
      hi = hi.cwiseMax(z);
    });
  } catch (const IntegrationError&) {
    return r;  // amplitudes unknown; the orbit's own figures still stand
  }
  for (int i = 0; i < positions; ++i) r.amplitudes[i] = 0.5 * (hi[i] - lo[i]);
  return r;
}

void print_orbit(std::FILE* out, const OdeSystem& system, const PeriodicOrbit& orbit,
                 const OrbitReport& report, const OrbitOptions& options) {
  const auto names = system.state_names();
  const auto& f = orbit.floquet;
  std::fprintf(out, "  period       %.12g s    frequency %.9g Hz\n", orbit.period,
               1.0 / orbit.period);
  std::fprintf(out, "  amplitudes  ");
  for (std::size_t i = 0; i < report.amplitudes.size(); ++i)
    std::fprintf(out, " %s %.6g", names[i].c_str(), report.amplitudes[i]);
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
  std::fprintf(out,
               "  work         %d segment%s, %s rtol %g: %ld integrations, %ld steps, %ld rhs and "
               "%ld sensitivity-rhs evaluations, %ld Jacobians\n",
               orbit.segments, orbit.segments > 1 ? "s" : "",
               to_string(options.shooting.flow.method).c_str(), options.shooting.flow.rtol,
               st.calls, st.steps, st.rhs_evaluations, st.variational_evaluations,
               st.jacobian_evaluations);
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

nlohmann::json orbit_json(const OdeSystem& system, const PeriodicOrbit& orbit,
                          const OrbitReport& report) {
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
  j["params"] = parameters_json(system);
  j["newton"] = {{"converged", orbit.newton.converged},
                 {"reason", orbit.newton.reason},
                 {"iterations", orbit.newton.iterations},
                 {"residual_norms", orbit.newton.residual_norms}};
  return j;
}

}  // namespace sympathy::cli
