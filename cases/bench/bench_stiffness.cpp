// Section (j) of sympathy bench. Each computation is find_periodic_orbit from the in-phase start
// (transient, period, Newton, every multiplier) at the default preset, timed whole in CPU seconds
// (median of three; one with --quick): as the preset runs it (the stiffness measured at the
// start, BDF above the threshold), with Adams forced (the preset without the switch) and with
// BDF and the forward-sensitivity module forced (what the switch chooses). The chosen column
// should be about the faster of the two forced ones plus the measurement's cost.
#include "cases/bench/bench_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <optional>
#include <vector>

#include "cases/cli/common.hpp"
#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

struct Platform {
  double k, c;  // N/m, N s/m
  const char* note;
};

enum class Run { Chosen, Adams, Bdf };

struct TimedPlatform {
  PeriodicOrbit orbit;
  double seconds = 0.0;
};

TimedPlatform timed_orbit(const CaseFile& file, const Platform& platform, Run run, int repeats) {
  const MetronomeModel model(
      file.spec("", {{"k", platform.k, "bench"}, {"c", platform.c, "bench"}}));
  const StartSpec& start = file.start("in-phase");
  OrbitOptions o;
  apply_accuracy(Accuracy::Default, o);
  if (run != Run::Chosen) o.switch_when_stiff = false;
  if (run == Run::Bdf) {
    o.shooting.flow.method = Method::BDF;
    o.shooting.flow.nonlinear_solver = NonlinearSolver::Newton;
    o.shooting.flow.sensitivities = Sensitivities::ForwardModule;
  }
  std::vector<double> times;
  TimedPlatform t;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t begin = std::clock();
    t.orbit = find_periodic_orbit(model, model.default_parameters(), file.initial_state(&start),
                                  file.invariant_subspace(start, model), o);
    times.push_back(static_cast<double>(std::clock() - begin) / CLOCKS_PER_SEC);
    if (!t.orbit.converged())
      throw std::runtime_error("bench (j): the in-phase orbit at k = " + format_double(platform.k) +
                               ", c = " + format_double(platform.c) +
                               " did not converge: " + t.orbit.newton.reason);
  }
  std::sort(times.begin(), times.end());
  t.seconds = times[times.size() / 2];
  return t;
}

}  // namespace

void bench_stiffness(const std::string& root, const std::string& out, bool quick,
                     std::ostream& md) {
  const CaseFile file = CaseFile::load(root + "cases/row2.toml");
  const int repeats = quick ? 1 : 3;
  const std::vector<Platform> platforms = {{14.7467, 0.0185, "Table II"},
                                           {1e6, 500.0, "Adams' side of the threshold"},
                                           {1e7, 1000.0, "BDF's side"},
                                           {1e6, 5000.0, "far stiff"}};
  md << "\n## (j) the integrator chosen by the measured stiffness\n\n"
        "The row setup's in-phase orbit from its start (find_periodic_orbit: transient, period, "
        "Newton, every multiplier) at the default preset, CPU seconds, median of "
     << repeats
     << ": as the preset runs it (the stiffness indicator measured: Adams' steps over BDF's on "
        "one plain period; BDF above "
     << table_number(kStiffIndicator, "%g")
     << "), with Adams forced and with BDF (forward sensitivities) forced.\n\n"
        "| k (N/m) | c (N s/m) | indicator | chosen | chosen (s) | Adams (s) | BDF (s) | trivial "
        "error | |\n|---|---|---|---|---|---|---|---|---|\n";
  CsvWriter table(out + "/stiffness.csv", {"k", "c", "indicator", "chosen", "chosen_seconds",
                                           "adams_seconds", "bdf_seconds", "trivial_error"});
  for (const Platform& p : platforms) {
    const TimedPlatform chosen = timed_orbit(file, p, Run::Chosen, repeats);
    const bool slow = quick && p.c >= 5000.0;  // forced Adams takes seconds there
    const std::optional<TimedPlatform> adams =
        slow ? std::nullopt
             : std::optional<TimedPlatform>(timed_orbit(file, p, Run::Adams, repeats));
    const TimedPlatform bdf = timed_orbit(file, p, Run::Bdf, repeats);
    const double indicator = chosen.orbit.stiffness ? chosen.orbit.stiffness->indicator : NAN;
    const std::string method = to_string(chosen.orbit.method);
    const std::string adams_seconds = adams ? table_number(adams->seconds, "%.3f") : "-";
    table.row(std::vector<std::string>{
        table_number(p.k, "%g"), table_number(p.c, "%g"), table_number(indicator, "%.3g"), method,
        table_number(chosen.seconds, "%.3f"), adams ? adams_seconds : "",
        table_number(bdf.seconds, "%.3f"),
        table_number(chosen.orbit.floquet.trivial_error, "%.1e")});
    md << "| " << table_number(p.k, "%g") << " | " << table_number(p.c, "%g") << " | "
       << table_number(indicator, "%.3g") << " | " << method << " | "
       << table_number(chosen.seconds, "%.3f") << " | " << adams_seconds << " | "
       << table_number(bdf.seconds, "%.3f") << " | "
       << table_number(chosen.orbit.floquet.trivial_error, "%.1e") << " | " << p.note << " |\n";
    std::printf("(j) k = %g, c = %g: indicator %.3g, %s %.3f s; Adams %s s, BDF %.3f s\n", p.k, p.c,
                indicator, method.c_str(), chosen.seconds, adams_seconds.c_str(), bdf.seconds);
    std::fflush(stdout);
  }
}

}  // namespace sympathy::bench
