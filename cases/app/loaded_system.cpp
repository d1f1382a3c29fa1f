#include "cases/app/loaded_system.hpp"

#include <algorithm>

#include "cases/app/start_data.hpp"
#include "sympathy/cases/metronome_describer.hpp"
#include "sympathy/cases/state_describer.hpp"

namespace sympathy::app {

LoadedSystem::LoadedSystem(const std::string& path, const std::string& params,
                           const std::vector<Assignment>& sets,
                           const std::optional<std::string>& start_data, const std::string& what,
                           const std::optional<SavedStart>& saved,
                           std::optional<Escapement> escapement)
    : sets_(sets) {
  if (case_file_kind(path) == "equations") {
    if (escapement)
      throw InputError(path +
                       ": an equation case file has no escapement (expected a metronome "
                       "case file where an escapement is asked for)");
    equations_.emplace(load_equations(path, params, sets, start_data));
    require_differentiable(*equations_->build.system, path + ": sign() in its equations", what,
                           "equations without sign() for " + what);
    recorded_ = equations_->start_data;
    describer_ = std::make_unique<StateDescriber>(*equations_->build.system);
  } else {
    metronomes_.emplace(load_case(path, params, sets));
    if (escapement) metronomes_->spec.escapement = *escapement;
    model_ = std::make_unique<MetronomeModel>(metronomes_->spec);
    require_differentiable(*model_, path + ": key 'escapement': the impulsive escapement (eq. 2)",
                           what, "escapement = \"half\" or \"double\"");
    describer_ = std::make_unique<MetronomeDescriber>(*model_);
    if (start_data)
      recorded_ = read_recorded_period(*start_data, model_->state_names(), this->path());
  }
  if (saved) saved_ = read_saved_orbit(*saved, system());
}

void LoadedSystem::scale_data_time(double period) {
  if (recorded_) scale_time(*recorded_, period);
}

const std::string& LoadedSystem::path() const {
  return equations_ ? equations_->file.path() : metronomes_->file.path();
}

std::vector<std::pair<std::string, std::string>> LoadedSystem::inputs() const {
  std::vector<std::pair<std::string, std::string>> files{{"case file", path()}};
  if (equations_ && !equations_->file.plugin().empty())
    files.emplace_back("plug-in source", equations_->file.plugin());
  if (recorded_) files.emplace_back("--start-data", recorded_->path);
  if (saved_) files.emplace_back("--parent", saved_->path);
  return files;
}

const std::string& LoadedSystem::params() const {
  return equations_ ? equations_->params : metronomes_->params;
}

const OdeSystem& LoadedSystem::system() const {
  if (equations_) return *equations_->build.system;
  return *model_;
}

std::string LoadedSystem::build_note() const {
  return equations_ ? describe_build(equations_->build) : std::string();
}

void LoadedSystem::require_parameter(const std::string& option, const std::string& name) const {
  const auto names = system().parameter_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw InputError(option + " " + name + ": not a parameter of " + path() +
                     "; expected one of: " + join(names));
}

std::vector<std::pair<std::string, double>> ParameterWindow::ends() const {
  std::vector<std::pair<std::string, double>> e{{"--from", from}, {"--to", to}};
  if (at) e.push_back({"--at", *at});
  return e;
}

double LoadedSystem::value_of(const std::string& parameter) const {
  if (metronomes_) return metronomes_->spec.get(parameter);
  return system().parameter(equations_->values, system().parameter_index(parameter));
}

std::vector<std::pair<std::string, double>> LoadedSystem::set_values(const std::string& set) const {
  std::vector<std::pair<std::string, double>> r;
  if (metronomes_) {
    const ModelSpec s = metronomes_->file.spec(set);
    for (const auto& name : s.parameter_names()) r.emplace_back(name, s.get(name));
  } else {
    const Eigen::VectorXd values = equations_->file.parameter_values(set);
    const auto names = equations_->file.parameter_names();
    for (std::size_t i = 0; i < names.size(); ++i) r.emplace_back(names[i], values[i]);
  }
  return r;
}

void LoadedSystem::check_range(const std::string& parameter,
                               const std::vector<std::pair<std::string, double>>& values) const {
  for (const auto& [option, value] : values) {
    if (metronomes_) {
      check_parameter_range(metronomes_->spec, parameter, {value}, option + ": ");
    } else {
      auto sets = sets_;
      sets.push_back({parameter, value, option + " " + format_number(value)});
      equations_->file.parameter_values(equations_->params, sets);
    }
  }
}

void LoadedSystem::require_orbits() const {
  if (!equations_) return;
  check_start_data_system(recorded_, system(), path());
  check_period_known(*equations_);
}

void LoadedSystem::require_autonomous(const std::string& what) const {
  if (equations_) check_autonomous(*equations_, what);
}

BranchSource LoadedSystem::source(const std::string& start, const std::vector<Assignment>& initial,
                                  const std::optional<RecordedPeriod>& data) const {
  const ParameterValues values = equations_ ? equations_->values : model_->default_parameters();
  if (saved_ && !data)
    return {system(),       *describer_,         saved_->values,
            saved_->state0, InvariantSubspace(), "saved " + saved_->description,
            saved_->period};
  if (data)
    return {system(),     *describer_,         values,
            data->state0, InvariantSubspace(), "data " + data->path,
            data->period};
  if (equations_) {
    const EquationCase& file = equations_->file;
    const StartSpec* named = start.empty() ? nullptr : &file.start(start);
    return {system(),
            *describer_,
            equations_->values,
            file.initial_state(named, initial),
            InvariantSubspace(),
            start.empty() ? std::string("states") : start,
            std::nullopt};
  }
  if (start.empty()) throw InputError("--start is required");
  const StartSpec& named = metronomes_->file.start(start);
  return {system(),
          *describer_,
          model_->default_parameters(),
          metronomes_->file.initial_state(&named, initial),
          metronomes_->file.invariant_subspace(named, *model_),
          named.name,
          std::nullopt};
}

std::vector<std::string> LoadedSystem::start_names() const {
  return equations_ ? equations_->file.start_names() : metronomes_->file.start_names();
}

InvariantSubspace LoadedSystem::subspace(const std::string& start) const {
  if (equations_ || start.empty()) return InvariantSubspace();
  return metronomes_->file.invariant_subspace(metronomes_->file.start(start), *model_);
}

FitModel LoadedSystem::fit_model() const {
  if (equations_)
    return equation_fit_model(equations_->file, *equations_->build.system, equations_->values);
  return metronome_fit_model(metronomes_->file, metronomes_->spec, false);
}

}  // namespace sympathy::app
