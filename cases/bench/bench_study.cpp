// Section (i) of sympathy bench. The target for the whole Fig. 8 study is wall time (the
// two branches run side by side on two cores), so that is what is reported, the median of three
// runs, beside the CPU time of both threads and each branch's own seconds: the longer branch sets
// the wall time.
#include "cases/bench/bench_study.hpp"

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <vector>

#include "cases/app/study_run.hpp"
#include "cases/cli/common.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

struct StudyTiming {
  double wall = 0.0, cpu = 0.0;
  std::vector<std::string> names;
  std::vector<double> seconds;
  std::vector<std::size_t> points;
  std::vector<std::string> events;  // per branch: "NS 84.9297727, ..."
};

StudyTiming timed_study(const std::string& path, const std::string& out) {
  Arguments args("study", {path, "--out", out}, study_options(), {"STUDY"});
  const Stopwatch clock;
  const std::clock_t cpu = std::clock();
  StudyRun run = study_run(args);
  run_study_branches(run, nullptr);
  StudyTiming t;
  t.wall = clock.seconds();
  t.cpu = static_cast<double>(std::clock() - cpu) / CLOCKS_PER_SEC;
  for (std::size_t i = 0; i < run.results.size(); ++i) {
    if (!run.errors[i].empty())
      throw std::runtime_error("bench (i): branch " + run.study.branches[i].name + ": " +
                               run.errors[i]);
    const Branch& b = run.results[i];
    t.names.push_back(run.study.branches[i].name);
    t.seconds.push_back(b.seconds);
    t.points.push_back(b.points.size());
    std::string events;
    for (const auto& e : b.events) {
      char one[64];
      std::snprintf(one, sizeof one, "%s%s %.9g", events.empty() ? "" : ", ",
                    to_string(e.type).c_str(), e.parameter);
      events += one;
    }
    t.events.push_back(events);
  }
  return t;
}

}  // namespace

void bench_study(const std::string& root, const std::string& out, bool quick, std::ostream& md) {
  const std::string path = root + "cases/figures/fig08.toml";
  std::vector<StudyTiming> runs;
  for (int r = 0; r < (quick ? 1 : 3); ++r) runs.push_back(timed_study(path, out + "/study"));
  std::sort(runs.begin(), runs.end(),
            [](const StudyTiming& a, const StudyTiming& b) { return a.wall < b.wall; });
  const StudyTiming& median = runs[runs.size() / 2];
  md << "\n## (i) the Fig. 8 study from its file\n\n`sympathy study cases/figures/fig08.toml` "
        "as the command runs it: both branches side by side on two threads, starts included, "
        "the default preset; wall seconds (the target: 1 s), median of "
     << runs.size()
     << " runs, and the CPU seconds of both threads.\n\n"
        "| wall (s) | CPU (s) | branch | its seconds | points | events "
        "|\n|---|---|---|---|---|---|\n";
  CsvWriter table(out + "/study.csv",
                  {"wall_seconds", "cpu_seconds", "branch", "seconds", "points", "events"});
  for (std::size_t i = 0; i < median.names.size(); ++i) {
    char wall[32], cpu[32], seconds[32];
    std::snprintf(wall, sizeof wall, "%.3f", median.wall);
    std::snprintf(cpu, sizeof cpu, "%.3f", median.cpu);
    std::snprintf(seconds, sizeof seconds, "%.3f", median.seconds[i]);
    table.row(std::vector<std::string>{wall, cpu, median.names[i], seconds,
                                       std::to_string(median.points[i]), median.events[i]});
    md << "| " << (i == 0 ? wall : "") << " | " << (i == 0 ? cpu : "") << " | " << median.names[i]
       << " | " << seconds << " | " << median.points[i] << " | " << median.events[i] << " |\n";
  }
  std::printf("(i) Fig. 8 study: %.3f s wall (median of %zu), %.3f s CPU;", median.wall,
              runs.size(), median.cpu);
  for (std::size_t i = 0; i < median.names.size(); ++i)
    std::printf(" %s %.3f s (%zu points)", median.names[i].c_str(), median.seconds[i],
                median.points[i]);
  std::printf("\n");
  std::fflush(stdout);
}

}  // namespace sympathy::bench
