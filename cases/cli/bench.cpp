// sympathy bench: error against run time for the row setup, over integrator settings.
//
// Problems: (a) the anti-phase orbit at Table II (period and multipliers), (b) the in-phase
// orbit at Table III (small amplitude), (c) the first stability change of the anti-phase
// k-branch (the branch point near 47 N/m). Each against a reference computed at rtol 1e-13
// with the turning-point pulse resolved; the reference's own change from rtol 1e-12 is
// reported as the level below which errors are not resolved. Orbits start from the same guess
// (the orbit's state and period moved by 1e-3), so each setting does its own Newton iterations.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "continuation/continuation.hpp"
#include "core/csv.hpp"

namespace sympathy::cli {

namespace {

struct Setting {
  std::string name;
  FlowOptions flow;
  int segments = 1;
};

struct Result {
  bool converged = false;
  double period = 0.0;
  std::vector<std::complex<double>> multipliers;  // nontrivial
  double trivial_error = NAN;
  double parameter = 0.0;  // (c): the located branch point
  double seconds = 0.0;
  FlowStatistics flow;
  int iterations = 0;
  std::string note;
};

Setting setting(const std::string& name, Method method, double rtol, int segments = 1,
                LinearSolver solver = LinearSolver::Dense,
                Derivatives derivatives = Derivatives::Model, bool resolve = true) {
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

OrbitOptions orbit_options(const Setting& s) {
  OrbitOptions o;
  o.shooting.flow = s.flow;
  o.shooting.segments = s.segments;
  // Newton cannot get below the integration's own error: ask for what the tolerance allows.
  o.newton.residual_tolerance = std::max(1e-10, 20.0 * s.flow.rtol);
  return o;
}

std::vector<std::complex<double>> nontrivial(const FloquetAnalysis& f) {
  std::vector<std::complex<double>> v;
  for (const auto& m : f.multipliers)
    if (!m.trivial) v.push_back(m.value);
  return v;
}

// Largest distance between the multipliers and the reference's, matched nearest first.
double multiplier_error(std::vector<std::complex<double>> a, std::vector<std::complex<double>> b) {
  if (a.size() != b.size()) return INFINITY;
  double worst = 0.0;
  while (!a.empty()) {
    std::size_t bi = 0, bj = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      for (std::size_t j = 0; j < b.size(); ++j)
        if (std::abs(a[i] - b[j]) < std::abs(a[bi] - b[bj])) {
          bi = i;
          bj = j;
        }
    worst = std::max(worst, std::abs(a[bi] - b[bj]));
    a.erase(a.begin() + bi);
    b.erase(b.begin() + bj);
  }
  return worst;
}

Result solve_orbit(const MetronomeModel& model, const PeriodicOrbit& guess,
                   const InvariantSubspace& subspace, const Setting& s) {
  Result r;
  const auto start = std::chrono::steady_clock::now();
  try {
    const auto orbit =
        solve_periodic_orbit(model, guess.state0, guess.period, subspace, orbit_options(s));
    r.converged = orbit.converged();
    r.period = orbit.period;
    r.multipliers = nontrivial(orbit.floquet);
    r.trivial_error = orbit.floquet.trivial_error;
    r.flow = orbit.flow;
    r.iterations = orbit.newton.iterations;
    if (!r.converged) r.note = orbit.newton.reason;
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// The first stability change of the anti-phase branch between k = 44 and 50 N/m.
Result locate_branch_point(MetronomeModel& model, const PeriodicOrbit& at44, const Setting& s) {
  Result r;
  const auto start = std::chrono::steady_clock::now();
  try {
    ContinuationOptions o;
    o.lower = 44.0;
    o.upper = 50.0;
    o.orbit = orbit_options(s);
    o.corrector_tolerance = o.orbit.newton.residual_tolerance;
    const int k = model.parameter_index("k");
    model.set_parameter(k, 44.0);
    Continuation c(model, k, o);
    const Branch b = c.run(at44, +1);
    for (const auto& e : b.events)
      if (e.type == BifurcationType::BranchPoint) {
        r.parameter = e.parameter;
        r.converged = e.located;
        break;
      }
    if (r.parameter == 0.0) r.note = "no branch point found (" + b.stop_reason + ")";
    r.flow = b.flow;
    for (const auto& p : b.points) r.iterations += p.iterations;
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::string format(double v, const char* f = "%.2e") {
  if (!std::isfinite(v)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

}  // namespace

int run_bench(const std::vector<std::string>& argv) {
  Arguments args("bench", argv,
                 {{"--out", "DIR", false, "where bench.csv and bench.md go (default out/bench)"},
                  {"--quick", "", false, "fewer tolerances (for a smoke run)"}},
                 {});
  Stopwatch clock;
  const std::string out = args.text("--out", "out/bench");
  std::filesystem::create_directories(out);
  const bool quick = args.flag("--quick");
  const std::string root =
      std::filesystem::exists("cases/row2.toml") ? "" : SYMPATHY_SOURCE_DIR "/";
  const CaseFile file = CaseFile::load(root + "cases/row2.toml");

  // The settings compared: tolerance sweeps of the defaults' families, and each alternative
  // at a few tolerances.
  std::vector<Setting> settings;
  std::vector<double> sweep =
      quick ? std::vector<double>{1e-6, 1e-9, 1e-12}
            : std::vector<double>{1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  const std::vector<double> few =
      quick ? std::vector<double>{1e-9} : std::vector<double>{1e-8, 1e-10, 1e-12};
  for (double t : sweep)
    settings.push_back(setting("BDF, dense, model derivatives", Method::BDF, t));
  for (double t : sweep) settings.push_back(setting("Adams", Method::Adams, t));
  for (double t : few) settings.push_back(setting("BDF, 5 segments", Method::BDF, t, 5));
  for (double t : few)
    settings.push_back(setting("BDF, KLU", Method::BDF, t, 1, LinearSolver::KLU));
  // Difference-quotient sensitivities cost ~500x more at rtol 1e-9 and fail at 1e-10: the
  // sweep shows where they stop.
  const std::vector<double> dq =
      quick ? std::vector<double>{1e-7} : std::vector<double>{1e-6, 1e-8, 1e-9, 1e-10};
  for (double t : dq)
    settings.push_back(setting("BDF, difference quotients", Method::BDF, t, 1, LinearSolver::Dense,
                               Derivatives::DifferenceQuotients));
  for (double t : few)
    settings.push_back(setting("BDF, pulse stepped over", Method::BDF, t, 1, LinearSolver::Dense,
                               Derivatives::Model, false));

  struct Problem {
    std::string name, params, start;
  };
  const std::vector<Problem> orbits{{"(a) anti-phase orbit, Table II", "table2", "anti-phase"},
                                    {"(b) in-phase orbit, Table III", "table3", "in-phase"}};
  CsvWriter csv(
      out + "/bench.csv",
      {"problem", "setting", "rtol", "period_error", "multiplier_error", "parameter_error",
       "trivial_multiplier_error", "seconds", "rhs_evaluations", "sensitivity_rhs_evaluations",
       "jacobians", "newton_iterations", "converged", "note"});
  std::ostringstream md;
  md << "# sympathy bench: error against run time (row setup)\n\n";
  const Setting reference = setting("reference", Method::BDF, 1e-13);
  const Setting check = setting("check", Method::BDF, 1e-12);
  auto emit = [&](const std::string& problem, const Setting& s, const Result& r,
                  double period_error, double mu_error, double k_error) {
    csv.row(std::vector<std::string>{
        problem, s.name, format(s.flow.rtol, "%.0e"), format(period_error), format(mu_error),
        format(k_error), format(r.trivial_error), format(r.seconds, "%.4f"),
        std::to_string(r.flow.rhs_evaluations), std::to_string(r.flow.variational_evaluations),
        std::to_string(r.flow.jacobian_evaluations), std::to_string(r.iterations),
        r.converged ? "yes" : "no", r.note});
    csv.flush();
    md << "| " << s.name << " | " << format(s.flow.rtol, "%.0e") << " | "
       << (std::isnan(period_error) ? format(k_error) : format(period_error)) << " | "
       << (std::isnan(mu_error) ? std::string("-") : format(mu_error)) << " | "
       << format(r.trivial_error) << " | " << format(r.seconds, "%.3f") << " | "
       << r.flow.rhs_evaluations << " | " << r.flow.variational_evaluations << " | "
       << r.flow.jacobian_evaluations << " | " << r.iterations << " | "
       << (r.converged ? "" : "not converged") << " |\n";
  };

  for (const auto& p : orbits) {
    MetronomeModel model(file.spec(p.params));
    const auto& start = file.start(p.start);
    const InvariantSubspace subspace = file.invariant_subspace(start, model);
    PeriodicOrbit guess =
        find_periodic_orbit(model, file.initial_state(&start), subspace, OrbitOptions{});
    // Every setting converges by itself from the same guess: the orbit moved by 1e-3.
    guess.state0 = subspace.project(guess.state0 * (1.0 + 1e-3));
    guess.period *= 1.0 + 1e-3;
    const Result ref = solve_orbit(model, guess, subspace, reference);
    const Result chk = solve_orbit(model, guess, subspace, check);
    const double ref_period = std::abs(chk.period - ref.period) / ref.period;
    const double ref_mu = multiplier_error(chk.multipliers, ref.multipliers);
    md << "## " << p.name << "\n\nReference: BDF rtol 1e-13, pulse resolved: period "
       << format(ref.period, "%.13f") << " s; its change from rtol 1e-12: period "
       << format(ref_period) << " (relative), multipliers " << format(ref_mu)
       << ". Errors below these are not resolved by the reference.\n\n"
       << "| setting | rtol | period error (rel.) | multiplier error | trivial error | "
          "seconds | rhs evals | sensitivity-rhs evals | Jacobians | Newton iterations | |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::printf("%s: reference period %.13f s (rtol 1e-12 differs by %.1e, multipliers %.1e)\n",
                p.name.c_str(), ref.period, ref_period, ref_mu);
    for (const auto& s : settings) {
      const Result r = solve_orbit(model, guess, subspace, s);
      const double pe = r.converged ? std::abs(r.period - ref.period) / ref.period : NAN;
      const double me = r.converged ? multiplier_error(r.multipliers, ref.multipliers) : NAN;
      emit(p.name, s, r, pe, me, NAN);
      std::printf("  %-32s rtol %.0e  period %s  multipliers %s  %.3f s%s\n", s.name.c_str(),
                  s.flow.rtol, format(pe).c_str(), format(me).c_str(), r.seconds,
                  r.converged ? "" : "  (not converged)");
      std::fflush(stdout);
    }
    md << "\n";
  }

  {
    const std::string name = "(c) first stability change of the anti-phase k-branch";
    MetronomeModel model(file.spec("table2"));
    model.set_parameter("k", 44.0);
    const auto& start = file.start("anti-phase");
    const InvariantSubspace subspace = file.invariant_subspace(start, model);
    const PeriodicOrbit at44 =
        find_periodic_orbit(model, file.initial_state(&start), subspace, OrbitOptions{});
    const Result ref = locate_branch_point(model, at44, reference);
    const Result chk = locate_branch_point(model, at44, check);
    const double ref_k = std::abs(chk.parameter - ref.parameter) / ref.parameter;
    md << "## " << name << "\n\nReference: BDF rtol 1e-13: k = " << format(ref.parameter, "%.12f")
       << " N/m; its change from rtol 1e-12: " << format(ref_k) << " (relative).\n\n"
       << "| setting | rtol | k error (rel.) | | trivial error | seconds | rhs evals | "
          "sensitivity-rhs evals | Jacobians | corrector iterations | |\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::printf("%s: reference k = %.12f (rtol 1e-12 differs by %.1e)\n", name.c_str(),
                ref.parameter, ref_k);
    for (const auto& s : settings) {
      if (s.flow.derivatives == Derivatives::DifferenceQuotients) continue;  // needs df/dk
      const Result r = locate_branch_point(model, at44, s);
      const double ke = r.converged ? std::abs(r.parameter - ref.parameter) / ref.parameter : NAN;
      emit(name, s, r, NAN, NAN, ke);
      std::printf("  %-32s rtol %.0e  k %s  %.3f s%s\n", s.name.c_str(), s.flow.rtol,
                  format(ke).c_str(), r.seconds, r.converged ? "" : "  (not located)");
      std::fflush(stdout);
    }
  }
  std::ofstream(out + "/bench.md") << md.str();
  std::printf("wrote %s/bench.csv and %s/bench.md; run time %.1f s\n", out.c_str(), out.c_str(),
              clock.seconds());
  return 0;
}

}  // namespace sympathy::cli
