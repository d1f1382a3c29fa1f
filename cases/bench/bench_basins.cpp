// Section (k) of sympathy bench. The targets (runs per second per core at least 5 times
// the full runs' at Table III and 2 times at k = 60, with the same classes for 99.5% of the
// starts) are measured here, one thread, the whole runs' wall time.
#include "cases/bench/bench_basins.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sympathy/cases/basin_study.hpp"
#include "sympathy/cases/case_file.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::bench {

namespace {

struct BasinCase {
  std::string label, params;
  double k = 0.0;  // NaN: the set's own
};

struct BasinSetting {
  std::string label;
  bool early = false;
  Method method = Method::BDF;
};

struct BasinOutcome {
  double seconds = 0.0;
  std::vector<BasinRun> runs;
};

BasinOutcome run_basins(const CaseFile& file, const BasinCase& c, const BasinSetting& s, int starts,
                        double t_end) {
  std::vector<Assignment> sets;
  if (!std::isnan(c.k)) sets.push_back({"k", c.k, "bench"});
  const ModelSpec spec = file.spec(c.params, sets);
  BasinOptions o;
  const double k = spec.get("k");
  o.grid = {GridAxis{"k", k, k, 1}};
  o.starts = starts;
  o.t_end = t_end;
  o.flow =
      s.method == Method::ERK ? BasinOptions::classification_flow() : BasinOptions::default_flow();

  o.early_stop = s.early;
  if (s.early)
    for (const auto& name : file.start_names()) {
      const StartSpec& start = file.start(name);
      o.candidate_starts.push_back(
          {name, file.initial_state(&start), file.invariant_subspace(start, MetronomeModel(spec))});
    }
  const Stopwatch clock;
  const BasinStudy study(spec, file.initial_state(nullptr), o);
  BasinOutcome out;
  for (std::size_t t = 0; t < study.tasks(); ++t) out.runs.push_back(*study.run(study.task(t)));
  out.seconds = clock.seconds();
  return out;
}

}  // namespace

void bench_basins(const std::string& root, const std::string& out, bool quick, std::ostream& md) {
  const CaseFile file = CaseFile::load(root + "cases/row2.toml");
  std::vector<BasinCase> cases;
  if (!quick)
    for (double k : {20.0, 40.0, 47.5, 50.0, 55.0})
      cases.push_back({"k = " + format_number(k), "table2", k});
  cases.push_back({"k = 60", "table2", 60.0});
  if (!quick) cases.push_back({"k = 80", "table2", 80.0});
  cases.push_back({"Table III", "table3", std::nan("")});
  const int starts = quick ? 32 : 200;
  const double t_end = quick ? 100.0 : 300.0;
  const std::vector<BasinSetting> settings = {{"early, BDF rtol 1e-8", true, Method::BDF},
                                              {"early, ERK rtol 1e-6", true, Method::ERK}};
  md << "\n## (k) basin runs stopped when their fate is known\n\n"
     << starts << " starts of " << format_number(t_end)
     << " s per case (seed 1), one thread, candidate orbits included: the full-length runs (BDF at "
        "rtol 1e-8) against `--early-stop`; runs per second, the classes that agree with the full "
        "runs', the largest difference in the time to synchronize among them, the runs certified, "
        "and the median time from the full run's time to synchronize to the early stop.\n\n"
        "| case | setting | runs/s | speed-up | same class | max dt_sync (s) | certified | "
        "median stop - t_sync (s) |\n|---|---|---|---|---|---|---|---|\n";
  CsvWriter table(out + "/basins.csv",
                  {"case", "setting", "runs_per_second", "speedup", "same_class", "runs",
                   "max_dt_sync", "certified", "median_stop_after_sync"});
  for (const BasinCase& c : cases) {
    const BasinOutcome full =
        run_basins(file, c, {"full, BDF rtol 1e-8", false, Method::BDF}, starts, t_end);
    const double full_rate = full.runs.size() / full.seconds;
    char line[256];
    std::snprintf(line, sizeof line, "| %s | full, BDF rtol 1e-8 | %.2f | 1 | | | | |\n",
                  c.label.c_str(), full_rate);
    md << line;
    table.row(std::vector<std::string>{c.label, "full", format_double(full_rate), "1", "", "", "",
                                       "", ""});
    for (const BasinSetting& s : settings) {
      const BasinOutcome early = run_basins(file, c, s, starts, t_end);
      int same = 0, certified = 0;
      double dt = 0.0;
      std::vector<double> after;
      for (std::size_t i = 0; i < full.runs.size(); ++i) {
        const SyncResult &a = full.runs[i].sync, &b = early.runs[i].sync;
        if (a.name != b.name) continue;
        ++same;
        if (!std::isnan(a.time_to_sync) && !std::isnan(b.time_to_sync))
          dt = std::max(dt, std::abs(a.time_to_sync - b.time_to_sync));
        if (!early.runs[i].certified_by.empty()) {
          ++certified;
          after.push_back(early.runs[i].stopped_at - a.time_to_sync);
        }
      }
      std::sort(after.begin(), after.end());
      const double median = after.empty() ? std::nan("") : after[after.size() / 2];
      const double rate = early.runs.size() / early.seconds;
      std::snprintf(line, sizeof line, "| %s | %s | %.2f | %.2f | %d / %zu | %.2g | %d | %.1f |\n",
                    c.label.c_str(), s.label.c_str(), rate, rate / full_rate, same,
                    full.runs.size(), dt, certified, median);
      md << line;
      table.row(std::vector<std::string>{c.label, s.label, format_double(rate),
                                         format_double(rate / full_rate), std::to_string(same),
                                         std::to_string(full.runs.size()), format_double(dt),
                                         std::to_string(certified), format_double(median)});
      std::printf(
          "(k) %s, %s: %.2f runs/s (%.2fx the full runs'), %d of %zu the same class, "
          "max dt_sync %.2g s, %d certified\n",
          c.label.c_str(), s.label.c_str(), rate, rate / full_rate, same, full.runs.size(), dt,
          certified);
      std::fflush(stdout);
    }
  }
}

}  // namespace sympathy::bench
