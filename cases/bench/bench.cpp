// sympathy bench: error against run time for the row setup, over integrator settings.
//
// Problems: (a) the anti-phase orbit at Table II (period and multipliers), (b) the in-phase
// orbit at Table III (small amplitude), (c) the first stability change of the anti-phase
// k-branch (the branch point near 47 N/m). Each against a reference computed at rtol 1e-13
// with the turning-point pulse resolved; the reference's own change from rtol 1e-12 is
// reported as the level below which errors are not resolved. Orbits start from the same guess
// (the orbit's state and period moved by 1e-3), so each setting does its own Newton iterations.
// Sections (d) and (e) measure the cost of a continuation point and of one period against the
// number of metronomes; (f), the accuracy presets and integrators on a whole branch beside
// AUTO-07p's measured points, is in bench_branch.cpp; (g) in bench_identical.cpp; (h), equation
// case files generated against hand-written, in bench_equations.cpp; (i), the Fig. 8 study, in
// bench_study.cpp; (j), the integrator chosen by the measured stiffness, in bench_stiffness.cpp;
// (k), basin runs stopped when their fate is known, in bench_basins.cpp; (l), the paper's
// impulsive escapement (hybrid orbits) against the smoothed one at equal error, in
// bench_hybrid.cpp. The orbit sections' shared pieces are in bench_orbit.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>
#include <tuple>

#include "cases/bench/bench_basins.hpp"
#include "cases/bench/bench_branch.hpp"
#include "cases/bench/bench_equations.hpp"
#include "cases/bench/bench_hybrid.hpp"
#include "cases/bench/bench_identical.hpp"
#include "cases/bench/bench_orbit.hpp"
#include "cases/bench/bench_stiffness.hpp"
#include "cases/bench/bench_study.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

// The first stability change of the anti-phase branch between k = 44 and 50 N/m.
Result locate_branch_point(const MetronomeModel& model, const PeriodicOrbit& at44,
                           const Setting& s) {
  Result r;
  const Stopwatch clock;
  try {
    ContinuationOptions o;
    o.lower = 44.0;
    o.upper = 50.0;
    o.orbit = orbit_options(s);
    o.corrector_tolerance = o.orbit.newton.residual_tolerance;
    Continuation c(model, model.parameter_index("k"), o);
    const Branch b = c.run(at44, +1);
    for (const auto& e : b.events)
      if (e.type == BifurcationType::BranchPoint) {
        r.parameter = e.parameter;
        r.converged = e.located();
        break;
      }
    if (r.parameter == 0.0) r.note = "no branch point found (" + b.stop_reason + ")";
    r.flow = b.flow;
    for (const auto& p : b.points) r.iterations += p.iterations;
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  r.seconds = clock.seconds();
  return r;
}

std::string format(double v, const char* f = "%.2e") {
  return table_number(v, f);
}

// (d) A branch at default settings against the floor of a shooting method: one period's
// integration with the sensitivities a point needs (state and the parameter).
struct PointCost {
  std::string name;
  int points = 0;
  double seconds = 0.0;
  long integrations = 0;
  double period_sensitivities = 0.0;  // s, one period with state and parameter sensitivities
  double period_plain = 0.0;          // s, one period, state only
  int events = 0;                     // bifurcations located
  int points_stepping = 0;            // the same branch without detecting bifurcations
  double seconds_stepping = 0.0;
};

PointCost point_cost(const CaseFile& file, const std::string& params, const std::string& start,
                     double from, double to) {
  PointCost c;
  c.name = start + " branch, k " + format(from, "%g") + " to " + format(to, "%g") + " N/m (" +
           params + ")";
  MetronomeModel model(file.spec(params));
  const int k = model.parameter_index("k");
  const ParameterValues values = model.with_parameter(model.default_parameters(), k, from);
  const auto& s = file.start(start);
  const InvariantSubspace subspace = file.invariant_subspace(s, model);
  const PeriodicOrbit orbit =
      find_periodic_orbit(model, values, file.initial_state(&s), subspace, OrbitOptions{});
  if (!orbit.converged()) return c;
  ContinuationOptions o;
  o.lower = from;
  o.upper = to;
  Continuation run(model, k, o);
  const Branch b = run.run(orbit, +1);
  c.seconds = b.seconds;
  c.points = static_cast<int>(b.points.size()) - 1;  // the first is the start's
  c.integrations = b.flow.calls;
  c.events = static_cast<int>(b.events.size());
  // Stepping alone: the same branch with no bifurcation detected, hence none located.
  o.detect_bifurcations = false;
  Continuation stepping(model, k, o);
  const Branch undetected = stepping.run(orbit, +1);
  c.points_stepping = static_cast<int>(undetected.points.size()) - 1;
  c.seconds_stepping = undetected.seconds;
  Flow flow(model, o.orbit.shooting.flow);
  const int parameter[] = {k};
  c.period_sensitivities = median_seconds(5, [&] {
    flow.advance_with_sensitivities(orbit.state0, values, 0.0, orbit.period, true, parameter);
  });
  c.period_plain =
      median_seconds(5, [&] { flow.advance(orbit.state0, values, 0.0, orbit.period); });
  return c;
}

// (e) One period with the monodromy matrix against the number of metronomes: the row setup
// (2, in-phase) and cases/many (4 to 64 on a 2-D platform, splay), after a transient.
struct Scaling {
  int metronomes = 0, dimension = 0;
  std::string solver;
  double period = 0.0;
  double seconds = 0.0;  // one period with state sensitivities
  long steps = 0;
  std::string note;
};

// One transient and period estimate per case (the flow's own linear solver), then one period
// with the monodromy timed for each of `solvers` from the same state.
std::vector<Scaling> scaling(const std::string& path, const std::string& params,
                             const std::vector<LinearSolver>& solvers, double rtol) {
  const CaseFile file = CaseFile::load(path);
  MetronomeModel model(params.empty() ? file.spec() : file.spec(params));
  Scaling common;
  common.metronomes = model.metronome_count();
  common.dimension = model.dimension();
  const auto names = file.start_names();
  const bool splay = std::find(names.begin(), names.end(), "splay") != names.end();
  const auto& start = file.start(splay ? "splay" : "in-phase");
  FlowOptions plain;
  plain.rtol = 1e-7;
  plain.atol = 1e-9;
  Flow transient(model, plain);
  const ParameterValues values = model.default_parameters();
  const Eigen::VectorXd z = transient.advance(file.initial_state(&start), values, 0.0, 20.0);
  common.period = estimate_period(transient, values, z, 2.0, 1e-3);
  if (!(common.period > 0.0)) common.note = "no period found after the transient";
  std::vector<Scaling> rows;
  for (LinearSolver solver : solvers) {
    Scaling r = common;
    r.solver = to_string(solver);
    rows.push_back(r);
    if (!r.note.empty()) continue;
    FlowOptions o;
    o.rtol = rtol;
    o.atol = rtol * 1e-2;
    o.linear_solver = solver;
    try {
      Flow flow(model, o);
      rows.back().seconds = median_seconds(r.metronomes > 16 ? 1 : 3, [&] {
        flow.reset_statistics();
        flow.advance_with_sensitivities(z, values, 0.0, r.period);
      });
      rows.back().steps = flow.statistics().steps;
    } catch (const std::exception& e) {
      rows.back().note = e.what();
    }
  }
  return rows;
}

// Where and how the report was measured: run times mean little without the machine and the day.
std::string where_measured(const std::vector<std::string>& argv) {
  std::string cpu = "an unknown processor";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  char day[32] = "an unknown day";
  const std::time_t now = std::time(nullptr);
  std::strftime(day, sizeof day, "%Y-%m-%d", std::gmtime(&now));
  std::string command = "sympathy bench";
  for (const auto& a : argv) command += " " + a;
  return "Measured by `" + command + "` (sympathy " SYMPATHY_VERSION ") on " + day + ", on " + cpu +
         " with " + std::to_string(std::thread::hardware_concurrency()) +
         " hardware threads, each computation on one core unless stated.";
}

}  // namespace

int run_bench(const std::vector<std::string>& argv) {
  Arguments args("bench", argv, bench_options(), {});
  Stopwatch clock;
  const std::string out = args.text("--out", "out/bench");
  std::filesystem::create_directories(out);
  const bool quick = args.flag("--quick");
  const std::string sections = args.text("--sections", "abcdefghijkl");
  for (char ch : sections)
    if (ch < 'a' || ch > 'l')
      throw InputError("--sections: expected letters from a to l (e.g. abc), got '" + sections +
                       "'");
  // On a terminal, a line before each section: which, how many of how many, the time so far.
  ProgressLine line(args.flag("--quiet"));
  std::size_t started = 0;
  auto want = [&](char section) {
    if (sections.find(section) == std::string::npos) return false;
    if (line.enabled()) {
      std::fflush(stdout);
      std::fprintf(line.log(), "bench: section (%c), %zu of %zu, %s so far\n", section, ++started,
                   sections.size(), duration_text(clock.seconds()).c_str());
    }
    return true;
  };
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
  CsvWriter csv(out + "/bench.csv", bench_csv_columns());
  std::ostringstream md;
  md << "# sympathy bench: error against run time (row setup)\n\n"
     << where_measured(argv) << "\n\n";
  const Setting reference = reference_setting();
  const Setting check = check_setting();
  auto emit = [&](const std::string& problem, const Setting& s, const Result& r,
                  double period_error, double mu_error, double k_error) {
    csv.row(orbit_csv_row(problem, s, r, period_error, mu_error, k_error));
    md << "| " << s.name << " | " << format(s.flow.rtol, "%.0e") << " | "
       << (std::isnan(period_error) ? format(k_error) : format(period_error)) << " | "
       << (std::isnan(mu_error) ? std::string("-") : format(mu_error)) << " | "
       << format(r.trivial_error) << " | " << format(r.seconds, "%.3f") << " | "
       << r.flow.rhs_evaluations << " | " << r.flow.variational_evaluations << " | "
       << r.flow.jacobian_evaluations << " | " << r.iterations << " | "
       << (r.converged ? "" : "not converged") << " |\n";
  };

  for (const auto& p : orbits) {
    if (!want(p.name[1])) continue;
    MetronomeModel model(file.spec(p.params));
    const auto& start = file.start(p.start);
    const InvariantSubspace subspace = file.invariant_subspace(start, model);
    // Every setting converges by itself from the same guess: the orbit moved by 1e-3.
    const PeriodicOrbit guess = orbit_guess(model, file, start, subspace);
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

  if (want('c')) {
    const std::string name = "(c) first stability change of the anti-phase k-branch";
    MetronomeModel model(file.spec("table2"));
    const ParameterValues at_k44 =
        model.with_parameter(model.default_parameters(), model.parameter_index("k"), 44.0);
    const auto& start = file.start("anti-phase");
    const InvariantSubspace subspace = file.invariant_subspace(start, model);
    const PeriodicOrbit at44 =
        find_periodic_orbit(model, at_k44, file.initial_state(&start), subspace, OrbitOptions{});
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
  if (want('d')) {
    md << "\n## (d) cost of a continuation point\n\nDefault settings (BDF, rtol 1e-11). The floor "
          "of a shooting method is one period's integration with the sensitivities a point "
          "needs (state and parameter); the ratio is a point's time over it, with the bifurcations "
          "located and without (the same branch, nothing detected).\n\n"
       << "| branch | points | seconds | integrations | s per point | one period with "
          "sensitivities (s) | one period plain (s) | ratio | events located | ratio without "
          "locating |\n"
       << "|---|---|---|---|---|---|---|---|---|---|\n";
    CsvWriter cost(
        out + "/cost.csv",
        {"branch", "points", "seconds", "integrations", "seconds_per_point",
         "period_with_sensitivities", "period_plain", "ratio", "events", "ratio_without_locating"});
    std::vector<std::tuple<std::string, std::string, double, double>> branches{
        {"table2", "anti-phase", 10.0, 100.0}, {"table2", "in-phase", 25.0, 100.0}};
    if (quick)
      branches = {{"table2", "anti-phase", 40.0, 60.0}, {"table2", "in-phase", 60.0, 80.0}};
    for (const auto& [params, start, from, to] : branches) {
      const PointCost c = point_cost(file, params, start, from, to);
      const double per_point = c.points > 0 ? c.seconds / c.points : NAN;
      const double ratio = per_point / c.period_sensitivities;
      const double stepping = c.points_stepping > 0
                                  ? c.seconds_stepping / c.points_stepping / c.period_sensitivities
                                  : NAN;
      cost.row(std::vector<std::string>{c.name, std::to_string(c.points), format(c.seconds, "%.3f"),
                                        std::to_string(c.integrations), format(per_point, "%.4f"),
                                        format(c.period_sensitivities, "%.4f"),
                                        format(c.period_plain, "%.4f"), format(ratio, "%.2f"),
                                        std::to_string(c.events), format(stepping, "%.2f")});
      md << "| " << c.name << " | " << c.points << " | " << format(c.seconds, "%.2f") << " | "
         << c.integrations << " | " << format(per_point, "%.4f") << " | "
         << format(c.period_sensitivities, "%.4f") << " | " << format(c.period_plain, "%.4f")
         << " | " << format(ratio, "%.1f") << " | " << c.events << " | " << format(stepping, "%.1f")
         << " |\n";
      std::printf(
          "(d) %s: %d points in %.2f s, %.4f s per point; one period with sensitivities "
          "%.4f s, plain %.4f s; ratio %.1f (%d events located; without locating %.1f)\n",
          c.name.c_str(), c.points, c.seconds, per_point, c.period_sensitivities, c.period_plain,
          ratio, c.events, stepping);
      std::fflush(stdout);
    }
  }

  if (want('e')) {
    md << "\n## (e) one period with the monodromy matrix against the number of metronomes\n\n"
          "The row setup (2) and cases/many (4 to 64 metronomes on a 2-D platform, spread "
          "directions, every fourth detuned), splay start after a 20 s transient; BDF, rtol "
          "1e-9.\n\n"
       << "| metronomes | dimension | linear solver | period (s) | steps | seconds | |\n"
       << "|---|---|---|---|---|---|---|\n";
    CsvWriter table(out + "/scaling.csv", {"metronomes", "dimension", "linear_solver", "period",
                                           "steps", "seconds", "note"});
    std::vector<int> counts{2, 4, 8, 16, 32, 64};
    if (quick) counts = {2, 4, 8};
    for (int count : counts) {
      const std::string path = count == 2
                                   ? root + "cases/row2.toml"
                                   : root + "cases/many/many" + std::to_string(count) + ".toml";
      // Dense only while it is affordable: its Newton systems cost O(n^3) per setup and
      // O(n^2) per column solved, n + 1 columns per step.
      std::vector<LinearSolver> solvers{LinearSolver::Structured};
      if (count <= 16) solvers.insert(solvers.begin(), LinearSolver::Dense);
      for (const Scaling& r : scaling(path, count == 2 ? "table2" : "", solvers, 1e-9)) {
        table.row(std::vector<std::string>{
            std::to_string(r.metronomes), std::to_string(r.dimension), r.solver,
            format(r.period, "%.6f"), std::to_string(r.steps), format(r.seconds, "%.3f"), r.note});
        md << "| " << r.metronomes << " | " << r.dimension << " | " << r.solver << " | "
           << format(r.period, "%.4f") << " | " << r.steps << " | " << format(r.seconds, "%.3f")
           << " | " << r.note << " |\n";
        std::printf("(e) %2d metronomes (n = %3d), %s: period %.4f s, %ld steps, %.3f s %s\n",
                    r.metronomes, r.dimension, r.solver.c_str(), r.period, r.steps, r.seconds,
                    r.note.c_str());
        std::fflush(stdout);
      }
    }
  }
  if (want('f')) bench_branch_accuracy(root, quick, csv, md);
  if (want('g')) bench_identical(root, out, quick, md);
  if (want('h')) bench_equations(root, quick, md);
  if (want('i')) bench_study(root, out, quick, md);
  if (want('j')) bench_stiffness(root, out, quick, md);
  if (want('k')) bench_basins(root, out, quick, md);
  if (want('l')) bench_hybrid(root, quick, csv, md);
  write_file_atomically(out + "/bench.md", md.str());
  std::printf("wrote %s/bench.csv and %s/bench.md; run time %.1f s\n", out.c_str(), out.c_str(),
              clock.seconds());
  return 0;
}

}  // namespace sympathy::bench
