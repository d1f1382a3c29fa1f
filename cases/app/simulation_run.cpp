#include "cases/app/simulation_run.hpp"

#include <algorithm>
#include <cmath>

#include "cases/app/case_arguments.hpp"
#include "cases/app/requests.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/platform_model.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

SimulationRun prepare_simulation(const Arguments& args) {
  // The system, its start and what the summary watches: an equation case file's (every state
  // watched, the frequency from the first), the full metronome model, or with --locked-pendula
  // the platform alone (the pendula's states dropped).
  SimulationRun run;
  run.times = simulation_times(args);
  run.t_end = args.number("--t-end", 60.0);
  run.dt = args.number("--dt", 0.01);
  const bool locked = args.flag("--locked-pendula");
  std::shared_ptr<const OdeSystem>& system = run.system;
  std::vector<int>& angles = run.angles;
  std::vector<int>& watched = run.watched;
  Eigen::VectorXd& z0 = run.z0;
  std::string plugin_path;
  if (case_file_kind(args.positional(0)) == "equations") {
    if (locked) throw InputError("--locked-pendula: only for a metronome case file");
    const LoadedEquations e = load_equations(args);
    const StartSpec* start = args.has("--start") ? &e.file.start(*args.value("--start")) : nullptr;
    z0 = e.file.initial_state(start, args.assignments("--initial"));
    if (start)
      run.start_name = start->name;
    else if (!args.has("--initial"))
      run.start_name = "(the file's [states])";
    system = e.build.system;
    run.parameters = e.values;
    angles = {0};
    for (int i = 0; i < system->dimension(); ++i) watched.push_back(i);
    run.case_path = e.file.path();
    plugin_path = e.file.plugin();
    run.params = e.params;
    run.model_note = describe_build(e.build);
    run.directions = -1;  // no units
  } else {
    const LoadedCase c = load_case(args);
    const StartSpec* start = args.has("--start") ? &c.file.start(*args.value("--start")) : nullptr;
    if (!start && !args.has("--initial"))
      throw InputError("give --start NAME (one of: " + join(c.file.start_names()) +
                       ") or --initial VAR=VALUE");
    if (start) run.start_name = start->name;
    const Eigen::VectorXd z_case = c.file.initial_state(start, args.assignments("--initial"));
    z0 = z_case;
    if (locked) {
      auto platform = std::make_shared<PlatformModel>(c.spec);
      const auto case_names = c.file.state_names();
      const auto names = platform->state_names();
      for (const auto& a : args.assignments("--initial"))
        if (std::find(names.begin(), names.end(), a.key) == names.end())
          throw InputError(a.source + ": the pendula are locked (--locked-pendula); expected a " +
                           "state of the platform: " + join(names));
      z0.resize(platform->dimension());
      for (int i = 0; i < platform->dimension(); ++i)
        z0[i] =
            z_case[std::find(case_names.begin(), case_names.end(), names[i]) - case_names.begin()];
      for (int a = 0; a < platform->platform_directions(); ++a) watched.push_back(a);
      angles = {0};  // frequency and phases of x
      system = std::move(platform);
      run.model_note = "pendula locked (the platform alone)";
    } else {
      auto model = std::make_shared<MetronomeModel>(c.spec);
      for (int i = 0; i < model->metronome_count(); ++i) angles.push_back(model->angle_index(i));
      for (int a = 0; a < model->platform_directions(); ++a) watched.push_back(a);
      watched.insert(watched.end(), angles.begin(), angles.end());
      system = std::move(model);
      run.model_note = "escapement " + to_string(c.spec.escapement);
    }
    run.parameters = system->default_parameters();
    run.case_path = c.file.path();
    run.params = c.params;
    run.directions = c.spec.directions;
  }
  run.flow = simulation_flow_options(args);
  if (auto out = args.value("--out")) {
    check_distinct_outputs({{"--out", *out}},
                           {{"case file", run.case_path}, {"plug-in source", plugin_path}});
    run.out_path = *out;
  }
  return run;
}

void run_simulation(SimulationRun& run, const std::function<bool()>& stop_requested,
                    const std::function<void(double, const Eigen::VectorXd&)>& on_sample) {
  Flow flow(*run.system, run.flow);
  const auto names = run.system->state_names();
  std::unique_ptr<CsvWriter> csv;
  if (!run.out_path.empty()) {
    std::vector<std::string> header{"t"};
    header.insert(header.end(), names.begin(), names.end());
    csv = std::make_unique<CsvWriter>(run.out_path, header);
  }
  OscillationAnalyzer analyzer(run.angles, run.watched, std::min(10.0, 0.5 * run.t_end));
  std::vector<double> row(names.size() + 1);
  try {
    // A stop ends the run after the current output sample; the rows written are whole.
    run.interrupted = flow.sample_until(run.z0, run.parameters, 0.0, run.times,
                                        [&](double t, const Eigen::VectorXd& z) {
                                          analyzer.add(t, z);
                                          if (csv) {
                                            row[0] = t;
                                            for (int i = 0; i < z.size(); ++i) row[i + 1] = z[i];
                                            csv->row(row);
                                          }
                                          if (on_sample) on_sample(t, z);
                                          return stop_requested && stop_requested();
                                        });
  } catch (const IntegrationError& e) {
    run.failure = e.what();  // keep what was computed
  }
  if (csv) csv->close();
  run.summary = analyzer.summary();
  run.statistics = flow.statistics();
  run.note = flow.two_solutions();
}

}  // namespace sympathy::app
