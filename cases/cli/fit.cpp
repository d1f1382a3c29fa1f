// sympathy fit: a case's parameters fitted to a recorded time series by least squares.
#include <cmath>
#include <cstdio>
#include <optional>

#include "cases/app/fit_run.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"

namespace sympathy::cli {

namespace {

// Units of a state by its name: platform in m, pendula in rad.
std::string unit(const std::string& state) {
  const bool velocity = state.size() > 1 && state[0] == 'v';
  const std::string position = velocity ? state.substr(1) : state;
  const std::string base = (position == "x" || position == "y") ? "m" : "rad";
  return velocity ? base + "/s" : base;
}

std::string short_number(double v, int digits = 2) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, v);
  return buffer;
}

}  // namespace

int run_fit(const std::vector<std::string>& argv) {
  Arguments args("fit", argv, fit_options(), {"CASE"});
  exit_on_interrupt();
  Stopwatch clock;
  const FitSetup setup = fit_setup(args);
  const auto& equations = setup.equations;
  const std::string& case_path = setup.case_path;
  const std::string& params = setup.params;
  const TrajectoryFitOptions& o = setup.options;
  const FitRun run = run_fit(setup);
  const PreparedFit& fit = run.fit;
  const TrajectoryFitResult& r = run.result;
  // Units of the recorded columns: the metronome model's (m, rad); an equation case file's
  // states have none.
  const auto unit_of = [&](const std::string& state) {
    return equations ? std::string() : unit(state);
  };
  const Recording& rec = fit.recording;
  const auto states = fit.model->state_names();

  // The report.
  std::printf("sympathy fit %s  params %s  data %s\n", case_path.c_str(),
              params.empty() ? "(none)" : params.c_str(), rec.path.c_str());
  if (equations) std::printf("  %s\n", describe_build(equations->build).c_str());
  std::string columns;
  for (const auto& col : rec.columns) columns += (columns.empty() ? "" : ", ") + col;
  std::printf("  model        %s; %d samples of %s, t = %g .. %g s\n",
              fit.model_description.c_str(), rec.samples(), columns.c_str(), rec.times.front(),
              rec.times.back());
  std::printf("  initial      ");
  for (std::size_t i = 0; i < states.size(); ++i)
    std::printf("%s%s %.6g (%s)", i ? "  " : "", states[i].c_str(),
                fit.problem.initial_state[static_cast<int>(i)], fit.initial_source[i].c_str());
  std::printf("\n");
  for (const auto& stage : r.stages)
    std::printf("  %-12s %s: %d evaluations, RSS %.6g -> %.6g in %.2f s; %s\n", stage.name.c_str(),
                stage.method.c_str(), stage.evaluations, stage.rss_start, stage.rss_end,
                stage.seconds, stage.stop_reason.c_str());
  std::printf("  fitted       %-10s %-18s %-12s %-10s %s\n", "name", "value", "std. error",
              "relative", "start");
  for (int j = 0; j < r.unknowns; ++j) {
    const double rel = r.errors[j] / std::abs(r.values[j]);
    std::printf("               %-10s %-18.10g %-12s %-10s %.6g\n", fit.unknowns[j].c_str(),
                r.values[j], short_number(r.errors[j]).c_str(),
                std::isfinite(rel) ? (short_number(100.0 * rel) + "%").c_str() : "-", r.start[j]);
  }
  std::printf("  residuals    RMS");
  for (std::size_t k = 0; k < rec.columns.size(); ++k)
    std::printf(" %s %.4g%s%s", rec.columns[k].c_str(), r.column_rms[static_cast<int>(k)],
                equations ? "" : " ", unit_of(rec.columns[k]).c_str());
  std::printf("; %d residuals, %d unknowns; s^2 = RSS/(N-p) = %.4g, residuals scaled by",
              r.residuals, r.unknowns, r.sigma2);
  for (std::size_t k = 0; k < rec.columns.size(); ++k)
    std::printf("%s %s %.3g%s%s", k ? "," : "", rec.columns[k].c_str(),
                fit.problem.column_scale[static_cast<int>(k)], equations ? "" : " ",
                unit_of(rec.columns[k]).c_str());
  std::printf("\n");
  std::string correlations;
  for (int a = 0; a < r.unknowns; ++a)
    for (int b = a + 1; b < r.unknowns; ++b)
      if (std::isfinite(r.errors[a]) && std::isfinite(r.errors[b])) {
        char buffer[64];
        std::snprintf(buffer, sizeof buffer, " %+.3f", r.correlation(a, b));
        correlations += " " + fit.unknowns[a] + "~" + fit.unknowns[b] + buffer;
      }
  if (!correlations.empty()) std::printf("  correlation %s\n", correlations.c_str());
  for (const auto& lost : r.undetermined) {
    std::string who;
    for (int j : lost) who += (who.empty() ? "" : ", ") + fit.unknowns[j];
    std::printf(
        "  NOT DETERMINED  the data fix only a combination of %s (rank %d of %d, "
        "condition %.2g): free fewer of them\n",
        who.c_str(), r.rank, r.unknowns, r.condition);
  }
  // The first row's noise is in the initial state unless it is fitted.
  std::string from_data;
  for (std::size_t k = 0; k < rec.columns.size(); ++k) {
    bool fitted = false;
    for (const auto& f : fit.problem.initial) fitted = fitted || f.component == rec.components[k];
    if (!fitted &&
        r.column_rms[static_cast<int>(k)] > 1e-6 * fit.problem.column_scale[static_cast<int>(k)])
      from_data += (from_data.empty() ? "" : ",") + rec.columns[k];
  }
  if (!from_data.empty())
    std::printf(
        "  note         the initial %s is the first row's, noise included; with noisy data "
        "fit it too (--free-initial %s)\n",
        from_data.c_str(), from_data.c_str());
  // A fit that explains little of the data's variation is likely a local minimum.
  const double explained = explained_variation(run);
  if (explained < 0.9)
    std::printf(
        "  note         the model explains only %.0f%% of the data's variation: a local "
        "minimum? (--global searches start/10 .. start*10)\n",
        100.0 * std::max(explained, 0.0));
  std::printf("  result       %s: %s\n", r.converged ? "converged" : "NOT CONVERGED",
              r.stop_reason.c_str());
  std::printf(
      "  work         %d evaluations (%d with sensitivities); %s rtol %g, atol %g: %ld "
      "steps, %ld rhs evaluations\n",
      r.evaluations, r.jacobian_evaluations, to_string(o.flow.method).c_str(), o.flow.rtol,
      o.flow.atol, r.statistics.steps, r.statistics.rhs_evaluations);

  const std::string csv_path = args.text("--csv", "");
  if (!csv_path.empty()) write_fitted_series(csv_path, setup, run);
  // The fitted case file.
  const bool determined = run.determined();
  std::string written;
  if (auto path = args.value("--out")) {
    if (!r.converged || !determined) {
      std::printf("  not written  %s: the fit %s\n", path->c_str(),
                  !r.converged ? "did not converge" : "leaves parameters undetermined");
    } else {
      const auto edits = write_fitted_case(*path, setup, run);
      std::printf("  wrote        %s:", path->c_str());
      for (const auto& e : edits) std::printf("\n                 %s", e.c_str());
      std::printf("\n");
      written = *path;
    }
  }
  const double seconds = clock.seconds();
  std::printf("  run time     %.3f s\n", seconds);
  if (auto path = args.value("--json"))
    write_fit_json(*path, setup, run, csv_path, written, seconds);
  return r.converged && determined ? 0 : 4;
}

}  // namespace sympathy::cli
