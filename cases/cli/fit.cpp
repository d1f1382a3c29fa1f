// sympathy fit: a case's parameters fitted to a recorded time series by least squares.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cases/app/fit_setup.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"
#include "sympathy/cases/case_writer.hpp"
#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::cli {

namespace {

// Units of a state by its name: platform in m, pendula in rad.
std::string unit(const std::string& state) {
  const bool velocity = state.size() > 1 && state[0] == 'v';
  const std::string position = velocity ? state.substr(1) : state;
  const std::string base = (position == "x" || position == "y") ? "m" : "rad";
  return velocity ? base + "/s" : base;
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char buffer[32];
  std::strftime(buffer, sizeof buffer, "%Y-%m-%d", std::localtime(&now));
  return buffer;
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
  const auto& metronomes = setup.c;
  const std::string& case_path = setup.case_path;
  const std::string& params = setup.params;
  const FitRequest& request = setup.request;
  const TrajectoryFitOptions& o = setup.options;
  PreparedFit fit = setup.prepare();
  // Units of the recorded columns: the metronome model's (m, rad); an equation case file's
  // states have none.
  const auto unit_of = [&](const std::string& state) {
    return equations ? std::string() : unit(state);
  };
  const Recording& rec = fit.recording;
  const auto states = fit.model->state_names();

  const TrajectoryFitResult r = fit_trajectory(*fit.model, fit.problem, o);
  const int np = static_cast<int>(fit.problem.parameters.size());

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
  double total = 0.0;
  for (int k = 0; k < static_cast<int>(rec.columns.size()); ++k) {
    const Eigen::VectorXd column = rec.values.col(k);
    const double mean = column.mean();
    total += (column.array() - mean).square().sum() / std::pow(fit.problem.column_scale[k], 2);
  }
  const double explained = total > 0.0 ? 1.0 - r.rss / total : 1.0;
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

  // The fitted model at the data's times.
  if (auto path = args.value("--csv")) {
    std::vector<std::string> header{"t"};
    header.insert(header.end(), states.begin(), states.end());
    CsvWriter csv(*path, header);
    Eigen::VectorXd z0 = fit.problem.initial_state;
    for (std::size_t l = 0; l < fit.problem.initial.size(); ++l)
      z0[fit.problem.initial[l].component] = r.values[np + static_cast<int>(l)];
    Flow flow(*fit.model, o.flow);
    std::vector<double> row(states.size() + 1);
    flow.sample(z0, r.fitted_parameters, rec.times.front(), rec.times,
                [&](double t, const Eigen::VectorXd& z) {
                  row[0] = t;
                  for (int i = 0; i < z.size(); ++i) row[i + 1] = z[i];
                  csv.row(row);
                });
  }

  // The fitted case file.
  const bool determined = r.undetermined.empty();
  std::string written;
  if (auto path = args.value("--out")) {
    if (!r.converged || !determined) {
      std::printf("  not written  %s: the fit %s\n", path->c_str(),
                  !r.converged ? "did not converge" : "leaves parameters undetermined");
    } else {
      std::vector<NewValue> values;
      const std::string data_name = rec.path.substr(rec.path.find_last_of('/') + 1);
      for (int j = 0; j < np; ++j)
        values.push_back({fit.unknowns[j], r.values[j],
                          "fitted to " + data_name + ", std. error " + short_number(r.errors[j])});
      for (const auto& a : args.assignments("--set")) {
        bool fitted = false;
        for (int j = 0; j < np; ++j) fitted = fitted || fit.unknowns[j] == a.key;
        if (!fitted)
          values.push_back(
              {a.key, metronomes->spec.get(a.key), "from " + a.source + " of the fit"});
      }
      std::string fitted_text;
      for (int j = 0; j < np; ++j)
        fitted_text += (j ? ", " : "") + fit.unknowns[j] + " = " + format_double(r.values[j]) +
                       " +- " + short_number(r.errors[j]);
      std::vector<std::string> header{
          "Written by sympathy fit on " + today() + " from " + case_path +
              (request.locked_pendula ? " (pendula locked: the platform alone)" : ""),
          "fitted: " + (np ? fitted_text : std::string("no parameters")),
          "to " + rec.path + " (" + columns + ", " + std::to_string(rec.samples()) +
              " samples), residual RMS " + short_number(r.column_rms.maxCoeff(), 4),
          ""};
      const auto edits =
          write_case_with_values(metronomes->file, metronomes->params, values, header, *path);
      std::printf("  wrote        %s:", path->c_str());
      for (const auto& e : edits) std::printf("\n                 %s", e.c_str());
      std::printf("\n");
      written = *path;
    }
  }
  const double seconds = clock.seconds();
  std::printf("  run time     %.3f s\n", seconds);

  if (auto path = args.value("--json")) {
    nlohmann::json j;
    j["case"] = case_path;
    j["params_set"] = params;
    j["data"] = rec.path;
    j["columns"] = rec.columns;
    j["samples"] = rec.samples();
    j["t_start"] = rec.times.front();
    j["t_end"] = rec.times.back();
    j["locked_pendula"] = request.locked_pendula;
    j["model"] = fit.model_description;
    j["state_names"] = states;
    std::vector<double> z0(fit.problem.initial_state.data(),
                           fit.problem.initial_state.data() + fit.problem.initial_state.size());
    j["initial_state"] = z0;
    j["initial_source"] = fit.initial_source;
    nlohmann::json unknowns = nlohmann::json::array();
    nlohmann::json values = nlohmann::json::object(), errors = nlohmann::json::object();
    for (int a = 0; a < r.unknowns; ++a) {
      unknowns.push_back({{"name", fit.unknowns[a]},
                          {"kind", a < np ? "parameter" : "initial"},
                          {"start", r.start[a]},
                          {"value", r.values[a]},
                          {"error", r.errors[a]}});
      values[fit.unknowns[a]] = r.values[a];
      errors[fit.unknowns[a]] = r.errors[a];
    }
    j["unknowns"] = unknowns;
    j["values"] = values;
    j["errors"] = errors;
    nlohmann::json cov = nlohmann::json::array(), cor = nlohmann::json::array();
    for (int a = 0; a < r.unknowns; ++a) {
      std::vector<double> row_cov(r.unknowns), row_cor(r.unknowns);
      for (int b = 0; b < r.unknowns; ++b) {
        row_cov[b] = r.covariance(a, b);
        row_cor[b] = r.correlation(a, b);
      }
      cov.push_back(row_cov);
      cor.push_back(row_cor);
    }
    j["covariance"] = cov;
    j["correlation"] = cor;
    j["rss_start"] = r.rss_start;
    j["rss"] = r.rss;
    j["residuals"] = r.residuals;
    j["sigma2"] = r.sigma2;
    nlohmann::json column_rms = nlohmann::json::object(), scale = nlohmann::json::object();
    for (std::size_t k = 0; k < rec.columns.size(); ++k) {
      column_rms[rec.columns[k]] = r.column_rms[static_cast<int>(k)];
      scale[rec.columns[k]] = fit.problem.column_scale[static_cast<int>(k)];
    }
    j["residual_rms"] = column_rms;
    j["column_scale"] = scale;
    j["rank"] = r.rank;
    j["condition"] = r.condition;
    nlohmann::json lost = nlohmann::json::array();
    for (const auto& l : r.undetermined) {
      std::vector<std::string> who;
      for (int k : l) who.push_back(fit.unknowns[k]);
      lost.push_back(who);
    }
    j["undetermined"] = lost;
    nlohmann::json stages = nlohmann::json::array();
    for (const auto& s : r.stages)
      stages.push_back({{"name", s.name},
                        {"method", s.method},
                        {"evaluations", s.evaluations},
                        {"rss_start", s.rss_start},
                        {"rss_end", s.rss_end},
                        {"stop_reason", s.stop_reason},
                        {"seconds", s.seconds}});
    j["stages"] = stages;
    j["evaluations"] = r.evaluations;
    j["jacobian_evaluations"] = r.jacobian_evaluations;
    j["converged"] = r.converged;
    j["stop_reason"] = r.stop_reason;
    j["params"] = parameters_json(*fit.model, r.fitted_parameters);
    j["integrator"] = {{"method", to_string(o.flow.method)},
                       {"rtol", o.flow.rtol},
                       {"atol", o.flow.atol},
                       {"steps", r.statistics.steps}};
    j["csv"] = args.text("--csv", "");
    j["out"] = written;
    j["seconds"] = seconds;
    write_file_atomically(*path, j.dump(2) + "\n");
  }
  return r.converged && determined ? 0 : 4;
}

}  // namespace sympathy::cli
