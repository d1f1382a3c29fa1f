#include "cases/cli/report.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>

#include "cases/cli/common.hpp"

namespace sympathy::cli {

// print_orbit's two parts: what the orbit is (only for one that converged), and how the search
// went.
void print_orbit_result(std::FILE* out, const OdeSystem& model, const PeriodicOrbit& orbit,
                        const std::vector<double>& amplitudes,
                        const std::vector<double>& phase_differences, const OrbitOptions& options,
                        const std::vector<double>& rms);
void print_orbit_search(std::FILE* out, const OdeSystem& model, const PeriodicOrbit& orbit,
                        const OrbitOptions& options);

void print_orbit(std::FILE* out, const OdeSystem& model, const PeriodicOrbit& orbit,
                 const std::vector<double>& amplitudes,
                 const std::vector<double>& phase_differences, const OrbitOptions& options,
                 const std::vector<double>& rms) {
  // A failure prints no result-like numbers (issue 32: "period 0 s, frequency inf Hz" and a
  // stability verdict above the FAILED line): what failed, Newton's history and the work.
  if (orbit.converged())
    print_orbit_result(out, model, orbit, amplitudes, phase_differences, options, rms);
  else
    std::fprintf(out,
                 "  no orbit     the search failed (%s): no period, multipliers or stability\n",
                 to_string(orbit.newton.outcome).c_str());
  print_orbit_search(out, model, orbit, options);
}

void print_orbit_result(std::FILE* out, const OdeSystem& model, const PeriodicOrbit& orbit,
                        const std::vector<double>& amplitudes,
                        const std::vector<double>& phase_differences, const OrbitOptions& options,
                        const std::vector<double>& rms) {
  const auto names = model.state_names();
  const auto& f = orbit.floquet;
  std::fprintf(out, "  period       %.12g s    frequency %.9g Hz\n", orbit.period,
               1.0 / orbit.period);
  std::fprintf(out, "  amplitudes  ");
  for (std::size_t i = 0; i < amplitudes.size(); ++i)
    std::fprintf(out, " %s %.6g", names[i].c_str(), amplitudes[i]);
  if (!rms.empty()) {
    std::fprintf(out, "\n  rms         ");
    for (std::size_t i = 0; i < rms.size(); ++i)
      std::fprintf(out, " %s %.9g", names[i].c_str(), rms[i]);
  }
  if (!phase_differences.empty()) {
    std::fprintf(out, "\n  phases to th1");
    for (std::size_t i = 0; i < phase_differences.size(); ++i)
      std::fprintf(out, " th%zu %+.6f", i + 2, phase_differences[i]);
  }
  std::fprintf(out, "\n  multipliers  (modulus, argument in rad)\n");
  for (const auto& m : f.multipliers) {
    std::fprintf(out, "    %.12f  %+.6f", m.modulus(), std::arg(m.value));
    if (m.trivial) std::fprintf(out, "   trivial");
    if (m.structural) std::fprintf(out, "   structural");
    if (m.symmetry == SymmetryKind::Breaking) std::fprintf(out, "   breaks symmetry");
    std::fprintf(out, "\n");
  }
  std::fprintf(out, "  stability    %s", to_string(f.stability).c_str());
  if (f.unstable_count > 0)
    std::fprintf(out, " (%d multiplier%s outside the unit circle)", f.unstable_count,
                 f.unstable_count > 1 ? "s" : "");
  std::fprintf(out, "; largest other |mu| = %.9f, tolerance %g\n", f.max_modulus,
               options.floquet.stability_tolerance);
  if (model.autonomous())
    std::fprintf(out, "  accuracy     Newton residual %.2e; trivial multiplier |mu - 1| = %.2e\n",
                 orbit.residual, f.trivial_error);
  else
    std::fprintf(out,
                 "  accuracy     Newton residual %.2e (a forced orbit, period the forcing's: no "
                 "trivial multiplier)\n",
                 orbit.residual);
  if (orbit.family_dimension > 0)
    std::fprintf(
        out,
        "  not isolated the shooting Jacobian has a %d-dimensional null space (a family of "
        "orbits, or a direction neutral to first order): %d structural multiplier%s at "
        "1, left out of the verdict\n",
        orbit.family_dimension, f.structural, f.structural > 1 ? "s" : "");
}

void print_orbit_search(std::FILE* out, const OdeSystem& model, const PeriodicOrbit& orbit,
                        const OrbitOptions& options) {
  const auto& s = orbit.newton;
  std::fprintf(out, "  newton       %s after %d iteration%s (%s); residuals",
               s.converged ? "converged" : "FAILED", s.iterations, s.iterations == 1 ? "" : "s",
               s.reason.c_str());
  for (double r : s.residual_norms) std::fprintf(out, " %.1e", r);
  std::fprintf(out, "\n");
  const auto& st = orbit.flow;
  const IntegrationAsRun run = integration_as_run(model, orbit, options);
  const FlowOptions& flow = run.flow;
  if (!orbit.reduction.empty())
    std::fprintf(out, "  symmetry     %s: %d states integrated instead of %d\n",
                 orbit.reduction.c_str(), run.integrated_dimension, model.dimension());
  std::fprintf(
      out,
      "  work         %d segment%s, %s%s, %s sensitivities, rtol %g: %ld integrations, %ld steps, "
      "%ld rhs and %ld sensitivity-rhs evaluations, %ld Jacobians%s\n",
      orbit.segments, orbit.segments > 1 ? "s" : "", to_string(flow.method).c_str(),
      run.solver.c_str(), to_string(flow.sensitivities).c_str(), flow.rtol, st.calls, st.steps,
      st.rhs_evaluations, st.variational_evaluations, st.jacobian_evaluations,
      orbit.stiffness ? ("; " + stiffness_note(*orbit.stiffness)).c_str() : "");
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

void print_newton_and_flow(std::FILE* out, const PeriodicOrbit& orbit) {
  std::fprintf(out, "  newton steps");
  for (double step : orbit.newton.step_norms) std::fprintf(out, " %.1e", step);
  std::fprintf(out, " (|dx|_inf; %d halvings; %s linear solves)\n", orbit.newton.halvings,
               orbit.newton.sparse ? "sparse LU" : "dense SVD");
  print_flow_statistics(out, orbit.flow);
}

void print_events(std::FILE* out, const Branch& branch) {
  const auto& events = branch.events;
  if (events.empty()) {
    std::fprintf(out, "  no bifurcations on this branch\n");
    return;
  }
  std::fprintf(out, "  %-4s %-20s %-11s %-14s %-28s %s\n", "type", branch.parameter_name.c_str(),
               "uncertainty", "period (s)", "crossing multiplier", "note");
  for (const auto& e : events) {
    const std::complex<double> crossing = e.crossing;
    char mu[64] = "";  // a user point (UZ) has no crossing multiplier
    if (e.type != BifurcationType::UserPoint)
      std::snprintf(mu, sizeof mu, "%.8f%+.8fi", crossing.real(), crossing.imag());
    std::string note = e.note;
    if (e.multiplicity > 1 && note.empty()) note = "multiplicity " + std::to_string(e.multiplicity);
    if (e.symmetry == SymmetryKind::Breaking && !branch.points.empty())
      note = "breaks " + branch.points.front().orbit.subspace.description() +
             (note.empty() ? "" : "; " + note);
    std::fprintf(out, "  %-4s %-20.12g %-11.1e %-14.10f %-28s %s\n",
                 (to_string(e.type) + (e.trusted() ? "" : "?")).c_str(), e.parameter, e.uncertainty,
                 e.period, mu, note.c_str());
  }
}

namespace {

std::string eigenvalue_text(std::complex<double> l) {
  char text[64];
  std::snprintf(text, sizeof text, "%.6g%+.6gi", l.real(), l.imag());
  return text;
}

// The eigenvalue nearest the imaginary axis: what crosses it at an event.
std::complex<double> critical(const Eigen::VectorXcd& eigenvalues) {
  std::complex<double> best = eigenvalues[0];
  for (const auto& l : eigenvalues)
    if (std::abs(l.real()) < std::abs(best.real())) best = l;
  return best;
}

}  // namespace

void print_equilibrium_events(std::FILE* out, const EquilibriumBranch& branch) {
  if (branch.events.empty()) {
    std::fprintf(out, "  no bifurcations on this branch\n");
    return;
  }
  std::fprintf(out, "  %-4s %-20s %-11s %-28s %s\n", "type", branch.parameter_name.c_str(),
               "uncertainty", "critical eigenvalue", "note");
  for (const auto& e : branch.events) {
    std::string note = e.note;
    if (e.hopf) {
      char text[160];
      std::snprintf(text, sizeof text, "omega %.10g, period %.10g, %s", e.hopf->omega,
                    e.hopf->period, describe_criticality(e.hopf->lyapunov).c_str());
      note = text + (note.empty() ? "" : "; " + note);
    }
    std::fprintf(out, "  %-4s %-20.12g %-11.1e %-28s %s\n",
                 (to_string(e.type) + (e.located ? "" : "?")).c_str(), e.parameter, e.uncertainty,
                 eigenvalue_text(critical(e.eigenvalues)).c_str(), note.c_str());
  }
}

void print_basins_walk(std::FILE* out, const BasinWalk& walk, const std::string& parameter,
                       const std::vector<NamedBranch>& branches,
                       const std::vector<NamedEquilibria>& equilibria) {
  const std::size_t starts = walk.values.empty() ? 0 : walk.values.front().runs.size();
  std::fprintf(out, "basins along %s, %zu starts each (share [95%% interval]):\n",
               parameter.c_str(), starts);
  for (const auto& v : walk.values) {
    std::string line = "  " + parameter + " = " + format_number(v.value) + ":";
    for (const auto& s : v.shares)
      if (s.proportion.count > 0)
        line.append("  ")
            .append(s.name)
            .append(" ")
            .append(format_number(std::round(s.proportion.share * 1000) / 1000))
            .append(" [")
            .append(format_number(std::round(s.proportion.lower * 1000) / 1000))
            .append(", ")
            .append(format_number(std::round(s.proportion.upper * 1000) / 1000))
            .append("]");
    std::string fates;
    for (const Fate f : {Fate::Certified, Fate::Reached, Fate::NewOrbit, Fate::Equilibrium,
                         Fate::Torus, Fate::Unresolved, Fate::Failed}) {
      const auto n = std::count_if(v.runs.begin(), v.runs.end(),
                                   [&](const AttractorFate& r) { return r.fate == f; });
      if (n > 0)
        fates.append(fates.empty() ? "" : ", ")
            .append(to_string(f))
            .append(" ")
            .append(std::to_string(n));
    }
    std::fprintf(out, "%s  (%s)\n", line.c_str(), fates.c_str());
  }
  if (walk.interrupted) std::fprintf(out, "  interrupted: the values after these were not run\n");
  for (const auto& c : share_changes(walk, branches, equilibria)) {
    std::string line = "  " + c.name + (c.appears ? " appears" : " disappears") + " between " +
                       parameter + " = " + format_number(c.before) + " and " +
                       format_number(c.after) + ":";
    if (c.appears ? c.present_before : c.present_after)
      line.append(" (an attractor at both: the starts' sampling)");
    else if (c.events.empty())
      line.append(" no located event of the branches there");
    for (std::size_t i = 0; i < c.events.size(); ++i) {
      const ShareChange::Event& e = c.events[i];
      line.append(i ? "," : "")
          .append(" ")
          .append(e.type)
          .append(" of ")
          .append(e.branch)
          .append(" at ")
          .append(format_number(e.parameter));
    }
    std::fprintf(out, "%s\n", line.c_str());
  }
}

}  // namespace sympathy::cli
