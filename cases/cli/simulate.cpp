// sympathy simulate: a time series from a start, as CSV, with a summary of where it ends.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cases/app/requests.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/report.hpp"
#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/platform_model.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/oscillation.hpp"

namespace sympathy::cli {

int run_simulate(const std::vector<std::string>& argv) {
  Arguments args("simulate", argv, simulate_options(), {"CASE"});

  Stopwatch clock;
  const std::vector<double> times = simulation_times(args);
  const double t_end = args.number("--t-end", 60.0);
  const double dt = args.number("--dt", 0.01);
  const bool locked = args.flag("--locked-pendula");

  // The system, its start and what the summary watches: an equation case file's (every state
  // watched, the frequency from the first), the full metronome model, or with --locked-pendula
  // the platform alone (the pendula's states dropped).
  std::shared_ptr<const OdeSystem> system;
  ParameterValues parameters;
  std::vector<int> angles, watched;
  Eigen::VectorXd z0;
  std::string case_path, params_name, start_name = "(--initial)", model_note, plugin_path;
  int directions = 0;  // leading states in metres (the platform's); the metronomes' in rad
  if (case_file_kind(args.positional(0)) == "equations") {
    if (locked) throw InputError("--locked-pendula: only for a metronome case file");
    const LoadedEquations e = load_equations(args);
    const StartSpec* start = args.has("--start") ? &e.file.start(*args.value("--start")) : nullptr;
    z0 = e.file.initial_state(start, args.assignments("--initial"));
    if (start)
      start_name = start->name;
    else if (!args.has("--initial"))
      start_name = "(the file's [states])";
    system = e.build.system;
    parameters = e.values;
    angles = {0};
    for (int i = 0; i < system->dimension(); ++i) watched.push_back(i);
    case_path = e.file.path();
    plugin_path = e.file.plugin();
    params_name = e.params;
    model_note = describe_build(e.build);
    directions = -1;  // no units
  } else {
    const LoadedCase c = load_case(args);
    const StartSpec* start = args.has("--start") ? &c.file.start(*args.value("--start")) : nullptr;
    if (!start && !args.has("--initial"))
      throw InputError("give --start NAME (one of: " + join(c.file.start_names()) +
                       ") or --initial VAR=VALUE");
    if (start) start_name = start->name;
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
      model_note = "pendula locked (the platform alone)";
    } else {
      auto model = std::make_shared<MetronomeModel>(c.spec);
      for (int i = 0; i < model->metronome_count(); ++i) angles.push_back(model->angle_index(i));
      for (int a = 0; a < model->platform_directions(); ++a) watched.push_back(a);
      watched.insert(watched.end(), angles.begin(), angles.end());
      system = std::move(model);
      model_note = "escapement " + to_string(c.spec.escapement);
    }
    parameters = system->default_parameters();
    case_path = c.file.path();
    params_name = c.params;
    directions = c.spec.directions;
  }
  Flow flow(*system, simulation_flow_options(args));

  const auto names = system->state_names();
  std::unique_ptr<CsvWriter> csv;
  if (auto out = args.value("--out")) {
    check_distinct_outputs({{"--out", *out}},
                           {{"case file", case_path}, {"plug-in source", plugin_path}});
    std::vector<std::string> header{"t"};
    header.insert(header.end(), names.begin(), names.end());
    csv = std::make_unique<CsvWriter>(*out, header);
  }
  OscillationAnalyzer analyzer(angles, watched, std::min(10.0, 0.5 * t_end));

  std::vector<double> row(names.size() + 1);
  std::string failure;
  const auto* stop = interrupt_flag();
  bool interrupted = false;
  try {
    // A signal stops the run after the current output sample; the rows written are whole.
    interrupted =
        flow.sample_until(z0, parameters, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
          analyzer.add(t, z);
          if (csv) {
            row[0] = t;
            for (int i = 0; i < z.size(); ++i) row[i + 1] = z[i];
            csv->row(row);
          }
          return stop->load();
        });
  } catch (const IntegrationError& e) {
    failure = e.what();  // keep what was computed; report below
  }
  if (csv) csv->close();

  const auto s = analyzer.summary();
  std::fprintf(stderr, "sympathy simulate %s  params %s  start %s  %s\n", case_path.c_str(),
               params_name.empty() ? "(none)" : params_name.c_str(), start_name.c_str(),
               model_note.c_str());
  std::fprintf(stderr, "  t = 0 .. %g s, output every %g s%s%s\n", t_end, dt,
               csv ? " -> " : " (no --out: time series not written)",
               csv ? csv->path().c_str() : "");
  if (!failure.empty()) std::fprintf(stderr, "  STOPPED: %s\n", failure.c_str());
  if (interrupted)
    std::fprintf(stderr, "  INTERRUPTED: the time series ends where the signal came\n");
  std::fprintf(stderr, "  over the last %g s:\n", std::min(10.0, 0.5 * t_end));
  if (s.frequency > 0.0)
    std::fprintf(stderr, "    frequency %.6g Hz (period %.6g s, %d cycles)\n", s.frequency,
                 1.0 / s.frequency, s.cycles);
  else
    std::fprintf(stderr, "    frequency: fewer than two cycles of %s\n", names[angles[0]].c_str());
  std::fprintf(stderr, "    amplitudes:");
  for (std::size_t k = 0; k < watched.size(); ++k)
    std::fprintf(stderr, " %s %.4g%s", names[watched[k]].c_str(), s.amplitudes[k],
                 directions < 0            ? ""
                 : watched[k] < directions ? " m"
                                           : " rad");
  std::fprintf(stderr, "\n");
  if (!s.phase_differences.empty()) {
    std::fprintf(stderr, "    phase differences to th1:");
    for (std::size_t k = 0; k < s.phase_differences.size(); ++k)
      std::fprintf(stderr, " %s %+.4f rad", names[angles[k + 1]].c_str(), s.phase_differences[k]);
    std::fprintf(stderr, "\n");
  }
  const auto& st = flow.statistics();
  std::fprintf(stderr,
               "  integrator: %s, rtol %g, atol %g; %ld steps, %ld rhs evaluations, %ld "
               "steep-zone band changes, %ld switchings\n",
               to_string(flow.options().method).c_str(), flow.options().rtol, flow.options().atol,
               st.steps, st.rhs_evaluations, st.steep_roots, st.switchings);
  if (args.flag("--verbose")) print_flow_statistics(stderr, st);
  std::fprintf(stderr, "  run time %.3f s\n", clock.seconds());
  if (!failure.empty()) return 3;
  return interrupted ? kInterrupted : 0;
}

}  // namespace sympathy::cli
