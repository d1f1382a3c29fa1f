#include "cases/app/fit_setup.hpp"

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

}  // namespace sympathy::app
