#include "cases/app/fit_run.hpp"

#include <ctime>

#include <nlohmann/json.hpp>

#include "sympathy/cases/case_writer.hpp"
#include "sympathy/continuation/branch_output.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>

#include "cases/app/start_data.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/option_check.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

namespace {

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

LocalMethod local_method(const std::string& name) {
  if (name == "slsqp") return LocalMethod::Slsqp;
  if (name == "lbfgs") return LocalMethod::Lbfgs;
  if (name == "mma") return LocalMethod::Mma;
  if (name == "bobyqa") return LocalMethod::Bobyqa;
  if (name == "neldermead") return LocalMethod::NelderMead;
  if (name == "lm") return LocalMethod::LevenbergMarquardt;
  throw InputError("--local " + name + ": expected slsqp, lbfgs, mma, bobyqa, neldermead or lm");
}

GlobalMethod global_method(const std::string& name) {
  if (name == "crs") return GlobalMethod::ControlledRandomSearch;
  if (name == "direct") return GlobalMethod::Direct;
  if (name == "isres") return GlobalMethod::Isres;
  if (name == "mlsl") return GlobalMethod::Mlsl;
  throw InputError("--global-method " + name + ": expected crs, direct, isres or mlsl");
}

}  // namespace

std::vector<std::string> names(const Arguments& args, const std::string& option) {
  std::vector<std::string> out;
  for (const auto& value : args.values(option)) {
    std::stringstream s(value);
    for (std::string item; std::getline(s, item, ',');) {
      if (item.empty()) throw InputError(option + " " + value + ": expected NAME[,NAME...]");
      out.push_back(item);
    }
  }
  return out;
}

FitSetup fit_setup(const Arguments& args) {
  FitSetup setup;
  // A metronome case file, or an equation case file (its system compiled, or from the cache).
  if (case_file_kind(args.positional(0)) == "equations") {
    for (const char* option : {"--locked-pendula", "--out"})
      if (args.has(option))
        throw InputError(std::string(option) + ": only for a metronome case file (" +
                         args.positional(0) +
                         " is an equation case file: its fitted values are in the report and "
                         "--json; run it with --set NAME=VALUE)");
    setup.equations = std::make_unique<LoadedEquations>(
        load_equations(args.positional(0), args.text("--params", ""), args.assignments("--set")));
    setup.case_path = setup.equations->file.path();
    setup.params = setup.equations->params;
  } else {
    setup.c = std::make_unique<LoadedCase>(load_case(args));
    setup.sets = args.assignments("--set");
    setup.case_path = setup.c->file.path();
    setup.params = setup.c->params;
  }
  const auto& equations = setup.equations;
  const auto& metronomes = setup.c;
  const std::string& case_path = setup.case_path;
  FitRequest& request = setup.request;
  request.data = *args.value("--data");
  request.free = names(args, "--free");
  request.free_initial = names(args, "--free-initial");
  request.locked_pendula = args.flag("--locked-pendula");
  if (args.has("--start"))
    request.start = equations ? &equations->file.start(*args.value("--start"))
                              : &metronomes->file.start(*args.value("--start"));
  request.initial = args.assignments("--initial");
  request.sigma = args.assignments("--sigma");
  for (const auto& r : args.values("--range")) request.ranges.push_back(parse_range(r, "--range"));

  TrajectoryFitOptions& o = setup.options;
  o.flow = flow_options(args, o.flow);
  o.local = local_method(args.text("--local", "lm"));
  o.polish = !args.flag("--no-polish");
  o.max_evaluations = args.integer("--max-evaluations", o.max_evaluations);
  if (o.max_evaluations < 1) throw InputError("--max-evaluations: expected a positive integer");
  if (args.flag("--global") || args.has("--global-method"))
    o.global = global_method(args.text("--global-method", "crs"));
  o.global_evaluations = args.integer("--global-evaluations", o.global_evaluations);
  if (o.global_evaluations < 10) throw InputError("--global-evaluations: expected at least 10");
  const int seed = args.integer("--seed", 1);
  if (seed < 0) throw InputError("--seed: expected a non-negative integer");
  o.seed = static_cast<unsigned>(seed);

  // Every output checked before any work: writable, and none replacing an input or another.
  for (const char* option : {"--out", "--json", "--csv"})
    if (auto path = args.value(option)) check_writable(*path, option);
  check_distinct_outputs({{"--out", args.text("--out", "")},
                          {"--json", args.text("--json", "")},
                          {"--csv", args.text("--csv", "")}},
                         {{"case file", case_path}, {"recording (--data)", request.data}});

  return setup;
}

PreparedFit FitSetup::prepare() const {
  return equations
             ? sympathy::prepare_fit(
                   equation_fit_model(equations->file, *equations->build.system, equations->values),
                   request)
             : sympathy::prepare_fit(c->file, c->spec, request);
}

FitRun run_fit(const FitSetup& setup, std::function<bool()> stop_requested) {
  FitRun run{setup.prepare(), {}};
  TrajectoryFitOptions options = setup.options;
  options.stop_requested = std::move(stop_requested);
  run.result = fit_trajectory(*run.fit.model, run.fit.problem, options);
  return run;
}

Eigen::VectorXd FitRun::fitted_initial_state() const {
  Eigen::VectorXd z0 = fit.problem.initial_state;
  for (std::size_t l = 0; l < fit.problem.initial.size(); ++l)
    z0[fit.problem.initial[l].component] = result.values[parameter_count() + static_cast<int>(l)];
  return z0;
}

double explained_variation(const FitRun& run) {
  const Recording& rec = run.fit.recording;
  double total = 0.0;
  for (int k = 0; k < static_cast<int>(rec.columns.size()); ++k) {
    const Eigen::VectorXd column = rec.values.col(k);
    const double mean = column.mean();
    total += (column.array() - mean).square().sum() / std::pow(run.fit.problem.column_scale[k], 2);
  }
  return total > 0.0 ? 1.0 - run.result.rss / total : 1.0;
}

void write_fitted_series(const std::string& path, const FitSetup& setup, const FitRun& run) {
  const PreparedFit& fit = run.fit;
  const Recording& rec = fit.recording;
  const auto states = fit.model->state_names();
  std::vector<std::string> header{"t"};
  header.insert(header.end(), states.begin(), states.end());
  CsvWriter csv(path, header);
  const Eigen::VectorXd z0 = run.fitted_initial_state();
  Flow flow(*fit.model, setup.options.flow);
  std::vector<double> row(states.size() + 1);
  flow.sample(z0, run.result.fitted_parameters, rec.times.front(), rec.times,
              [&](double t, const Eigen::VectorXd& z) {
                row[0] = t;
                for (int i = 0; i < z.size(); ++i) row[i + 1] = z[i];
                csv.row(row);
              });
}

std::vector<std::string> write_fitted_case(const std::string& path, const FitSetup& setup,
                                           const FitRun& run) {
  const PreparedFit& fit = run.fit;
  const TrajectoryFitResult& r = run.result;
  const Recording& rec = fit.recording;
  const int np = run.parameter_count();
  const auto& metronomes = setup.c;
  const std::string& case_path = setup.case_path;
  const FitRequest& request = setup.request;
  std::string columns;
  for (const auto& col : rec.columns) columns += (columns.empty() ? "" : ", ") + col;
  std::vector<NewValue> values;
  const std::string data_name = rec.path.substr(rec.path.find_last_of('/') + 1);
  for (int j = 0; j < np; ++j)
    values.push_back({fit.unknowns[j], r.values[j],
                      "fitted to " + data_name + ", std. error " + short_number(r.errors[j])});
  for (const auto& a : setup.sets) {
    bool fitted = false;
    for (int j = 0; j < np; ++j) fitted = fitted || fit.unknowns[j] == a.key;
    if (!fitted)
      values.push_back({a.key, metronomes->spec.get(a.key), "from " + a.source + " of the fit"});
  }
  std::string fitted_text;
  for (int j = 0; j < np; ++j)
    fitted_text += (j ? ", " : "") + fit.unknowns[j] + " = " + format_double(r.values[j]) + " +- " +
                   short_number(r.errors[j]);
  std::vector<std::string> header{
      "Written by sympathy fit on " + today() + " from " + case_path +
          (request.locked_pendula ? " (pendula locked: the platform alone)" : ""),
      "fitted: " + (np ? fitted_text : std::string("no parameters")),
      "to " + rec.path + " (" + columns + ", " + std::to_string(rec.samples()) +
          " samples), residual RMS " + short_number(r.column_rms.maxCoeff(), 4),
      ""};
  return write_case_with_values(metronomes->file, metronomes->params, values, header, path);
}

void write_fit_json(const std::string& path, const FitSetup& setup, const FitRun& run,
                    const std::string& csv, const std::string& out, double seconds) {
  const PreparedFit& fit = run.fit;
  const TrajectoryFitResult& r = run.result;
  const Recording& rec = fit.recording;
  const int np = run.parameter_count();
  const TrajectoryFitOptions& o = setup.options;
  const auto states = fit.model->state_names();
  nlohmann::json j;
  j["case"] = setup.case_path;
  j["params_set"] = setup.params;
  j["data"] = rec.path;
  j["columns"] = rec.columns;
  j["samples"] = rec.samples();
  j["t_start"] = rec.times.front();
  j["t_end"] = rec.times.back();
  j["locked_pendula"] = setup.request.locked_pendula;
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
  j["interrupted"] = r.interrupted;
  j["stop_reason"] = r.stop_reason;
  j["params"] = parameters_json(*fit.model, r.fitted_parameters);
  j["integrator"] = {{"method", to_string(o.flow.method)},
                     {"rtol", o.flow.rtol},
                     {"atol", o.flow.atol},
                     {"steps", r.statistics.steps}};
  j["csv"] = csv;
  j["out"] = out;
  j["seconds"] = seconds;
  write_file_atomically(path, j.dump(2) + "\n");
}

}  // namespace sympathy::app
