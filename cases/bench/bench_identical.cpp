// Section (g) of sympathy bench. Each computation is find_periodic_orbit from the case's in-phase
// start (the 60 s transient, the period estimate, Newton and the multipliers), as `sympathy orbit`
// runs it, at the library's defaults (BDF, rtol 1e-11), timed whole (median of three, one for
// the whole 64-metronome state). The reduction is checked against the whole computation: the
// largest distance between their multipliers, paired one to one by least distance, beside the
// whole computation's own accuracy figure (its trivial multiplier's distance from 1).
#include "cases/bench/bench_identical.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cases/cli/common.hpp"
#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/assignment.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

struct Timed {
  PeriodicOrbit orbit;
  double seconds = 0.0;
};

Timed timed_orbit(const std::string& path, bool use_symmetry, int repeats) {
  const CaseFile file = CaseFile::load(path);
  const MetronomeModel model(file.spec());
  const StartSpec& start = file.start("in-phase");
  const InvariantSubspace subspace = file.invariant_subspace(start, model);
  OrbitOptions o;
  o.use_symmetry = use_symmetry;
  std::vector<double> times;
  Timed t;
  for (int r = 0; r < repeats; ++r) {
    const Stopwatch clock;
    t.orbit = find_periodic_orbit(model, model.default_parameters(), file.initial_state(&start),
                                  subspace, o);
    times.push_back(clock.seconds());
  }
  std::sort(times.begin(), times.end());
  t.seconds = times[times.size() / 2];
  return t;
}

// Largest distance between two lists of multipliers paired by least total squared distance.
double multiplier_distance(const FloquetAnalysis& a, const FloquetAnalysis& b) {
  const int n = static_cast<int>(a.multipliers.size());
  if (n != static_cast<int>(b.multipliers.size())) return NAN;
  Eigen::MatrixXd cost(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      cost(i, j) = std::norm(a.multipliers[i].value - b.multipliers[j].value);
  const std::vector<int> column = least_cost_assignment(cost);
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, std::abs(a.multipliers[i].value - b.multipliers[column[i]].value));
  return worst;
}

std::string number(double v, const char* f = "%.3g") {
  return table_number(v, f);
}

}  // namespace

void bench_identical(const std::string& root, const std::string& out, bool quick,
                     std::ostream& md) {
  md << "\n## (g) the in-phase orbit of N identical metronomes with all its multipliers\n\n"
        "find_periodic_orbit from the in-phase start (60 s transient, period, Newton, every "
        "multiplier), BDF rtol 1e-11, in the symmetry reduction (the platform and two "
        "metronomes, the second standing for N - 1) and on the whole state. Multiplier "
        "difference: the largest distance between the two computations' multipliers, paired; "
        "the whole computation's accuracy: its trivial multiplier's distance from 1.\n\n"
     << "| metronomes | states | reduced (s) | reduced / row2 | whole (s) | multiplier difference "
        "| whole's trivial error |\n|---|---|---|---|---|---|---|\n";
  CsvWriter table(out + "/identical.csv",
                  {"metronomes", "states", "reduced_seconds", "ratio_to_row2", "whole_seconds",
                   "multiplier_difference", "whole_trivial_error"});
  std::vector<int> counts{2, 4, 8, 64};
  if (quick) counts = {2, 4, 8};
  double two = 0.0;
  for (int count : counts) {
    const std::string path =
        root + (count == 2 ? "cases/row2.toml" : "cases/row/row" + std::to_string(count) + ".toml");
    const Timed reduced = timed_orbit(path, true, 3);
    const Timed whole = timed_orbit(path, false, count > 8 ? 1 : 3);
    if (count == 2) two = reduced.seconds;
    const int states = static_cast<int>(reduced.orbit.state0.size());
    const double difference = multiplier_distance(reduced.orbit.floquet, whole.orbit.floquet);
    const double ratio = reduced.seconds / two;
    table.row(std::vector<std::string>{std::to_string(count), std::to_string(states),
                                       number(reduced.seconds, "%.3f"), number(ratio, "%.2f"),
                                       number(whole.seconds, "%.3f"), number(difference, "%.2e"),
                                       number(whole.orbit.floquet.trivial_error, "%.2e")});
    md << "| " << count << " | " << states << " | " << number(reduced.seconds, "%.3f") << " | "
       << number(ratio, "%.2f") << " | " << number(whole.seconds, "%.3f") << " | "
       << number(difference, "%.1e") << " | " << number(whole.orbit.floquet.trivial_error, "%.1e")
       << " |\n";
    std::printf(
        "(g) %2d identical metronomes (%3d states): reduced %.3f s (%.2f x row2), whole "
        "%.3f s, multipliers differ by %.1e (whole's trivial error %.1e)\n",
        count, states, reduced.seconds, ratio, whole.seconds, difference,
        whole.orbit.floquet.trivial_error);
    std::fflush(stdout);
  }
}

}  // namespace sympathy::bench
