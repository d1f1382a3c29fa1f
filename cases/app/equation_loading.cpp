#include "cases/app/equation_loading.hpp"

#include <cstdio>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

namespace {

// The file's parameter values and its system (compiled or from the cache), `recorded` checked
// already: everything is checked before the compiler runs; a compiler failure is not the user's
// input (a missing compiler or headers, or a bug of the generator) and says so.
LoadedEquations build_loaded(EquationCase file, const std::string& params,
                             const std::vector<Assignment>& sets,
                             std::optional<RecordedPeriod> recorded) {
  const std::string set = params.empty() ? file.default_parameter_set() : params;
  ParameterValues values = file.parameter_values(set, sets);
  EquationBuild build = build_equation_system(file, values);
  return {std::move(file), set, std::move(values), std::move(build), std::move(recorded)};
}

}  // namespace

LoadedEquations load_equations(const std::string& path, const std::string& params,
                               const std::vector<Assignment>& sets,
                               const std::optional<std::string>& start_data) {
  EquationCase file = EquationCase::load(path);
  file.parameter_values(params.empty() ? file.default_parameter_set() : params,
                        sets);  // the values' errors first
  std::optional<RecordedPeriod> recorded;
  if (start_data) {
    std::vector<int> angles;  // as the compiled system will declare them (angle_states)
    for (std::size_t i = 0; i < file.system().states.size(); ++i)
      if (file.system().states[i].angle) angles.push_back(static_cast<int>(i));
    recorded = read_recorded_period(*start_data, file.state_names(), file.path(), angles);
  }
  return build_loaded(std::move(file), params, sets, std::move(recorded));
}

void check_period_known(const LoadedEquations& e) {
  if (!e.build.system->autonomous() && !e.file.system().forcing_period && e.file.plugin().empty())
    throw InputError(e.file.path() +
                     ": its equations use t (a periodically forced system) and it declares no "
                     "forcing period; expected forcing_period = \"EXPRESSION\" (the forcing's "
                     "period from the parameters, e.g. \"2*pi/beta\") at the top of the file");
  if (!e.build.system->autonomous() && !(e.build.system->forcing_period(e.values.data()) > 0.0))
    throw InputError(e.file.path() + ": a periodically forced system whose forcing_period is " +
                     format_number(e.build.system->forcing_period(e.values.data())) +
                     " at these parameter values; expected a positive period");
}

void check_autonomous(const LoadedEquations& e, const std::string& what) {
  if (!e.build.system->autonomous())
    throw InputError(e.file.path() + ": its equations use t (a periodically forced system); " +
                     what +
                     " is for autonomous systems (a forced system's orbits: orbit, "
                     "continue and study)");
}

void check_start_data_system(const std::optional<RecordedPeriod>& recorded, const OdeSystem& system,
                             const std::string& case_path) {
  if (recorded && !system.autonomous())
    throw InputError("--start-data " + recorded->path + ": " + case_path +
                     " uses t (a periodically forced system), whose period is the forcing's, not "
                     "the recording's; expected an autonomous system (a forced one starts from its "
                     "[states] or a named start, with its forcing_period)");
}

std::string describe_build(const EquationBuild& build) {
  char seconds[32];
  std::snprintf(seconds, sizeof seconds, "%.2f", build.seconds);
  const std::string what = build.plugin.empty() ? "system" : "plug-in " + build.plugin;
  std::string s = build.compiled ? what + " compiled in " + std::string(seconds) +
                                       " s against the headers in " + build.include_dir
                                 : what + " from the cache";
  // A plug-in is code: say so each time it runs.
  if (!build.plugin.empty())
    s += " (a plug-in is C++ code, run as it is: use only plug-ins you trust)";
  s += " (" + build.library + ")";
  if (!build.rebuilt_because.empty()) s += "; the entry was rebuilt: " + build.rebuilt_because;
  return s;
}

}  // namespace sympathy::app
