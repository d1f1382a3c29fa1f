// A study's [[equilibria]] entries as `equilibria` runs: each one's request made from its table
// (the window, the start, the options load_study checked) and checked against its case before
// any work, then computed by the command's own run_equilibria (its CSV streamed as the command's
// --csv), switched at the BP of the entry it names once that one is computed.
#include <algorithm>
#include <filesystem>

#include "cases/app/study_run.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

void prepare_study_equilibria(StudyRun& run,
                              std::vector<std::pair<std::string, std::string>>& outputs) {
  const Study& study = run.study;
  for (std::size_t k = 0; k < study.equilibria.size(); ++k) {
    const StudyEquilibria& e = study.equilibria[k];
    const std::string where = study.path + ": equilibria '" + e.name + "': ";
    auto c = std::make_unique<LoadedSystem>(study.case_path, study.params, e.sets, std::nullopt,
                                            "equilibria", std::nullopt, study.escapement);
    c->require_autonomous("[[equilibria]] (equilibria)");
    const OdeSystem& system = c->system();
    const auto names = system.parameter_names();
    if (std::find(names.begin(), names.end(), study.parameter) == names.end())
      throw InputError(study.path + ": parameter '" + study.parameter + "' is not one of " +
                       c->path() + "'s: " + join(names));
    std::vector<std::pair<std::string, double>> ends{{where + "from", e.from},
                                                     {where + "to", e.to}};
    if (e.at) ends.emplace_back(where + "at", *e.at);
    c->check_range(study.parameter, ends);

    EquilibriaRequest r;
    EquilibriumProblem& problem = r.problem;
    problem.parameter = system.parameter_index(study.parameter);
    problem.from = e.from;
    problem.to = e.to;
    problem.at = e.at;
    r.switch_at = e.switch_at;
    if (!e.parent.empty()) {
      // At the BP of an entry listed before: its values and state are the parent's, given when
      // it has run; its prepared problem stands in until then.
      const auto parent = static_cast<std::size_t>(
          std::find_if(study.equilibria.begin(), study.equilibria.end(),
                       [&](const StudyEquilibria& o) { return o.name == e.parent; }) -
          study.equilibria.begin());
      problem.values = run.equilibria_requests[parent].problem.values;
      problem.start_state = Eigen::VectorXd::Zero(system.dimension());
      r.start = "the branch point BP" + std::to_string(e.switch_at) + " of the equilibria '" +
                e.parent + "'";
    } else {
      if (!c->equations() && e.start.empty() && !e.saved)
        throw InputError(where + "key 'start' is missing; expected the name of one of " +
                         c->path() + "'s starts: " + join(c->start_names()));
      EquilibriaStart start = equilibria_start(*c, e.start, e.initial, e.saved);
      problem.start_state = std::move(start.state);
      problem.values = std::move(start.values);
      r.start = start.name.empty() ? "the case's states" : start.name;
    }
    if (const std::string wrong = problem.problem_with(system); !wrong.empty())
      throw InputError(where + wrong);
    r.options = e.options;
    r.csv_path = run.out + "/" + study.name + "-" + e.name + ".csv";
    outputs.emplace_back("equilibria '" + e.name + "''s CSV", r.csv_path);
    run.equilibria_requests.push_back(std::move(r));
    run.equilibria_systems.push_back(std::move(c));
  }
  run.equilibria_results.resize(study.equilibria.size());
  run.equilibria_errors.resize(study.equilibria.size());
  if (study.equilibria.empty()) return;
  // The state of the diagram (plot_study), checked here so that a figure never fails on it.
  const auto states = run.equilibria_systems.front()->system().state_names();
  run.equilibria_axis = study.equilibria_axis.empty() ? states.front() : study.equilibria_axis;
  if (std::find(states.begin(), states.end(), run.equilibria_axis) == states.end())
    throw InputError(study.path + ": equilibria_axis '" + run.equilibria_axis +
                     "' is not a state of " + run.equilibria_systems.front()->path() +
                     "; expected one of: " + join(states));
}

void run_study_equilibria(StudyRun& run, std::size_t k, const std::atomic<bool>* stop,
                          const std::function<void(const std::string&)>& doing) {
  const StudyEquilibria& e = run.study.equilibria[k];
  EquilibriaRequest& r = run.equilibria_requests[k];
  if (!e.parent.empty()) {
    std::size_t p = 0;
    while (run.study.equilibria[p].name != e.parent) ++p;
    if (!run.equilibria_errors[p].empty() || !run.equilibria_results[p].started())
      throw std::runtime_error("its parent equilibria '" + e.parent + "' have no result");
    r.parent_branch = &run.equilibria_results[p];
  }
  EquilibriumCallbacks callbacks;
  callbacks.on_point = [&](const EquilibriumPoint& p) {
    doing(e.name + " " + run.study.parameter + " = " + format_number(p.parameter));
  };
  callbacks.stop_requested = [stop] { return stop && stop->load(); };
  run.equilibria_results[k] = run_equilibria(r, run.equilibria_systems[k]->system(), callbacks);
}

}  // namespace sympathy::app
