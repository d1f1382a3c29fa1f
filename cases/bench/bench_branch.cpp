#include "cases/bench/bench_branch.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <sstream>
#include <utility>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_loading.hpp"
#include "cases/cli/common.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

// How one run is set up: an accuracy preset (as --accuracy), or the shooting flow alone set to an
// integrator at a tolerance (as --method, --sensitivities and --rtol on top of the default).
struct BranchSetting {
  std::string name;
  std::optional<Accuracy> preset;
  FlowOptions flow;
  bool symmetry = true;  // OrbitOptions::use_symmetry: false computes the whole state throughout
};

struct BranchRun {
  std::vector<std::pair<std::string, double>> events;  // type, located k
  double trivial_error = 0.0;                          // largest over the branch's points
  double seconds = 0.0;
  // The process's CPU time over the run (one thread): on a machine shared with other builds the
  // wall time of a run grew 2-3 times (load average 5 on 2 cores) while this did not.
  double cpu_seconds = 0.0;
  FlowStatistics flow;
  int points = 0;
  bool trusted = true;  // every event trusted
  std::string note;
};

BranchSetting integrator(const std::string& name, Method method, Sensitivities sensitivities,
                         double rtol, ExplicitTable table = ExplicitTable::DormandPrince) {
  BranchSetting s;
  s.name = name;
  s.flow = OrbitOptions{}.shooting.flow;
  s.flow.method = method;
  s.flow.nonlinear_solver =
      method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
  s.flow.sensitivities = sensitivities;
  s.flow.explicit_table = table;
  s.flow.rtol = rtol;
  s.flow.atol = rtol * 1e-2;
  return s;
}

BranchSetting preset(const std::string& name, Accuracy accuracy) {
  BranchSetting s;
  s.name = name;
  s.preset = accuracy;
  OrbitOptions o;
  apply_accuracy(accuracy, o);
  s.flow = o.shooting.flow;
  return s;
}

// `sympathy continue cases/row2.toml --start anti-phase --param k --from 1 --to 100` in-process
// (no process start-up: a few milliseconds).
BranchRun run(const LoadedCase& c, const BranchRequest& branch, const BranchSetting& s) {
  BranchRun r;
  const Stopwatch clock;
  const std::clock_t cpu = std::clock();
  try {
    const MetronomeModel model(c.spec);
    BranchRequest request = branch;
    if (s.preset)
      apply_accuracy(*s.preset, request.continuation);
    else
      request.continuation.orbit.shooting.flow = s.flow;
    request.continuation.orbit.use_symmetry = s.symmetry;
    const Branch b = run_branch(c, model, request, nullptr);
    for (const auto& e : b.events) {
      r.events.emplace_back(to_string(e.type), e.located() ? e.parameter : NAN);
      r.trusted = r.trusted && e.trusted();
    }
    for (const auto& p : b.points)
      r.trivial_error = std::max(r.trivial_error, p.orbit.floquet.trivial_error);
    r.flow = b.flow;
    r.points = static_cast<int>(b.points.size());
  } catch (const std::exception& e) {
    r.note = e.what();
  }
  r.seconds = clock.seconds();
  r.cpu_seconds = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
  return r;
}

// Largest relative error of the located events against the reference's, the same types in the
// same order; infinite when an event is missing, extra or not located.
double event_error(const BranchRun& r, const BranchRun& reference) {
  if (r.events.size() != reference.events.size() || reference.events.empty()) return INFINITY;
  double worst = 0.0;
  for (std::size_t i = 0; i < r.events.size(); ++i) {
    if (r.events[i].first != reference.events[i].first || std::isnan(r.events[i].second))
      return INFINITY;
    worst = std::max(worst, std::abs(r.events[i].second - reference.events[i].second) /
                                std::abs(reference.events[i].second));
  }
  return worst;
}

std::string fmt(double v, const char* f = "%.2e") {
  if (!std::isfinite(v)) return "-";
  char b[32];
  std::snprintf(b, sizeof b, f, v);
  return b;
}

// AUTO-07p's measured anti-phase rows: "NTST n, NCOL m, DSMAX d" with error, trivial error and
// seconds, from the anchors file (comment lines start with '#').
struct AutoAnchor {
  std::string setting;
  double error = NAN, trivial = NAN, seconds = NAN;
  int points = 0;
};

std::vector<AutoAnchor> auto_anchors(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read AUTO-07p's anchors");
  std::vector<AutoAnchor> anchors;
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {  // branch,NTST,NCOL,EPSL,EPSS,DSMAX,points,error_rel,trivial_err_max,wall_s
      header = false;
      continue;
    }
    std::vector<std::string> f;
    std::stringstream fields(line);
    for (std::string x; std::getline(fields, x, ',');) f.push_back(x);
    if (f.size() != 10 || f[0] != "anti" || f[7] == "missed") continue;
    AutoAnchor a;
    a.setting = "AUTO-07p NTST " + f[1] + ", NCOL " + f[2] + ", EPSL " + f[3] + ", DSMAX " + f[5];
    a.points = std::stoi(f[6]);
    a.error = std::stod(f[7]);
    a.trivial = std::stod(f[8]);
    a.seconds = std::stod(f[9]);
    anchors.push_back(a);
  }
  return anchors;
}

}  // namespace

void bench_branch_accuracy(const std::string& root, bool quick, CsvWriter& csv, std::ostream& md) {
  const std::string problem = "(f) anti-phase k-branch, k 1 to 100 N/m";
  LoadedCase c{CaseFile::load(root + "cases/row2.toml"), "", {}};
  c.params = c.file.default_parameter_set();
  c.spec = c.file.spec(c.params);

  std::vector<BranchSetting> settings{preset("preset fast", Accuracy::Fast),
                                      preset("preset default", Accuracy::Default),
                                      preset("preset high", Accuracy::High)};
  // What the symmetry buys (shooting.hpp): the presets with every point computed on the whole
  // state.
  for (auto [name, accuracy] : {std::pair{"preset fast, whole state", Accuracy::Fast},
                                std::pair{"preset default, whole state", Accuracy::Default}}) {
    settings.push_back(preset(name, accuracy));
    settings.back().symmetry = false;
  }
  const auto F = Sensitivities::ForwardModule;
  const auto A = Sensitivities::Augmented;
  auto sweep = [&](const std::string& name, Method m, Sensitivities s, std::vector<double> tols,
                   ExplicitTable table = ExplicitTable::DormandPrince) {
    for (double t : tols) settings.push_back(integrator(name, m, s, t, table));
  };
  if (quick) {
    sweep("forward module, BDF", Method::BDF, F, {1e-11});
    sweep("ERK Dormand-Prince", Method::ERK, A, {1e-7});
  } else {
    sweep("forward module, BDF", Method::BDF, F, {1e-10, 1e-11, 1e-12});
    sweep("forward module, Adams", Method::Adams, F, {1e-11, 1e-12});
    sweep("augmented, Adams", Method::Adams, A, {1e-10, 1e-11, 5e-12, 1e-12});
    sweep("augmented, BDF", Method::BDF, A, {1e-11});
    sweep("ERK Dormand-Prince", Method::ERK, A, {1e-6, 1e-7, 1e-8, 1e-9, 1e-10});
    sweep("ERK Verner", Method::ERK, A, {1e-7, 1e-9}, ExplicitTable::Verner);
  }

  BranchRequest branch;  // what `continue` makes of the command line
  branch.start = c.file.start("anti-phase").name;
  branch.parameter.push_back('k');
  branch.from = 1.0;
  branch.to = 100.0;
  branch.progress = nullptr;
  // The reference on the whole state: independent of the symmetry's shortcuts.
  BranchSetting reference_setting = integrator("reference", Method::BDF, F, 1e-13);
  reference_setting.symmetry = false;
  const BranchRun reference = run(c, branch, reference_setting);
  md << "\n## " << problem << "\n\n"
     << "`sympathy continue cases/row2.toml --start anti-phase --param k --from 1 --to 100` in "
        "process, start and transient included. Error: the largest relative error of the located "
        "events against a reference at BDF rtol 1e-13 (";
  for (const auto& [type, k] : reference.events) md << type << " " << fmt(k, "%.10f") << "; ";
  md << fmt(reference.seconds, "%.1f")
     << " s); below about 1e-9 the corrector's and location's "
        "tolerances, not the integration, set it. Trivial: the largest |mu - 1| over the branch's "
        "points. AUTO-07p's rows are AUTO's own measurements (bench/anchors/auto07p_row_k.csv, "
        "whole process, another day: compare ratios within one run where you can).\n\n"
     << "| setting | rtol | event error (rel.) | trivial error | seconds | CPU seconds | steps | "
        "points | events trusted |\n|---|---|---|---|---|---|---|---|---|\n";
  std::printf("%s: reference %.2f s, %zu events\n", problem.c_str(), reference.seconds,
              reference.events.size());
  for (const auto& s : settings) {
    const BranchRun r = run(c, branch, s);
    const double error = event_error(r, reference);
    const bool ok = r.note.empty() && std::isfinite(error);
    csv.row(std::vector<std::string>{
        problem, s.name, fmt(s.flow.rtol, "%.0e"), "", "", fmt(error), fmt(r.trivial_error),
        fmt(r.seconds, "%.4f"), std::to_string(r.flow.rhs_evaluations),
        std::to_string(r.flow.variational_evaluations), std::to_string(r.flow.jacobian_evaluations),
        "", ok ? "yes" : "no", r.note, std::to_string(r.flow.steps), std::to_string(r.points),
        fmt(r.cpu_seconds, "%.4f"), "", ""});
    md << "| " << s.name << " | " << fmt(s.flow.rtol, "%.0e") << " | " << fmt(error) << " | "
       << fmt(r.trivial_error) << " | " << fmt(r.seconds, "%.3f") << " | "
       << fmt(r.cpu_seconds, "%.3f") << " | " << r.flow.steps << " | " << r.points << " | "
       << (r.trusted ? "yes" : "no") << " |\n";
    std::printf("  %-28s rtol %.0e  error %s  trivial %s  %.3f s (CPU %.3f s)  %ld steps%s\n",
                s.name.c_str(), s.flow.rtol, fmt(error).c_str(), fmt(r.trivial_error).c_str(),
                r.seconds, r.cpu_seconds, r.flow.steps,
                r.note.empty() ? "" : ("  " + r.note).c_str());
    std::fflush(stdout);
  }
  for (const auto& a : auto_anchors(root + "bench/anchors/auto07p_row_k.csv")) {
    csv.row(std::vector<std::string>{problem, a.setting, "-", "", "", fmt(a.error), fmt(a.trivial),
                                     fmt(a.seconds, "%.4f"), "", "", "", "", "AUTO-07p",
                                     "AUTO-07p's measurement (anchors file)", "",
                                     std::to_string(a.points), "", "", ""});
    md << "| " << a.setting << " (AUTO's measurement) | - | " << fmt(a.error) << " | "
       << fmt(a.trivial) << " | " << fmt(a.seconds, "%.3f") << " | - | - | " << a.points
       << " | - |\n";
  }
}

}  // namespace sympathy::bench
