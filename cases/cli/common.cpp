#include "cases/cli/common.hpp"

#include "sympathy/core/csv.hpp"

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <utility>

namespace sympathy::cli {

std::vector<OptionSpec> case_options() {
  return {
      {"--params", "NAME", false, "named parameter set of the case (default: the file's)"},
      {"--set", "KEY=VALUE", true, "set a model parameter (M, c, k, mp, d2, eps, kappa, ...)"},
  };
}

std::vector<OptionSpec> integrator_options() {
  return {
      {"--rtol", "R", false, "relative tolerance of the integrator"},
      {"--atol", "A", false, "absolute tolerance of the integrator"},
      {"--method", "bdf|adams", false, "linear multistep method (default bdf)"},
      {"--linear-solver", "dense|klu|structured", false,
       "linear solver of the BDF Newton iteration (default: structured, sparse plus low rank, for "
       "more than 3 metronomes; else dense)"},
  };
}

LoadedCase load_case(const Arguments& args) {
  LoadedCase c{CaseFile::load(args.positional(0)), "", {}};
  c.params = args.text("--params", c.file.default_parameter_set());
  c.spec = c.file.spec(c.params, args.assignments("--set"));
  return c;
}

FlowOptions flow_options(const Arguments& args, FlowOptions o) {
  o.rtol = args.number("--rtol", o.rtol);
  o.atol = args.number("--atol", o.atol);
  check_options(o.validate(), "");
  const std::string method = args.text("--method", o.method == Method::BDF ? "bdf" : "adams");
  if (method == "bdf") {
    o.method = Method::BDF;
    o.nonlinear_solver = NonlinearSolver::Newton;
  } else if (method == "adams") {
    o.method = Method::Adams;
    o.nonlinear_solver = NonlinearSolver::FixedPoint;
  } else {
    throw InputError("--method " + method + ": expected bdf or adams");
  }
  if (!args.has("--linear-solver")) return o;  // as given (by default the flow's own choice)
  const std::string solver = args.text("--linear-solver", "");
  if (solver == "dense")
    o.linear_solver = LinearSolver::Dense;
  else if (solver == "klu")
    o.linear_solver = LinearSolver::KLU;
  else if (solver == "structured")
    o.linear_solver = LinearSolver::Structured;
  else
    throw InputError("--linear-solver " + solver + ": expected dense, klu or structured");
  return o;
}

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  if (g_interrupted.exchange(true)) std::_Exit(130);
}

// The same file whatever the spelling (a relative or absolute path, a symbolic link; a file
// that does not exist yet by its normalized absolute path).
std::string identity(const std::string& path) {
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  return ec ? std::filesystem::absolute(path).lexically_normal().string() : canonical.string();
}

}  // namespace

const std::atomic<bool>* interrupt_flag() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, on_interrupt);
  return &g_interrupted;
}

void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                            const std::vector<std::pair<std::string, std::string>>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const auto& [option, path] = outputs[i];
    if (path.empty()) continue;
    for (const auto& [input_name, input] : inputs)
      if (!input.empty() && identity(path) == identity(input))
        throw InputError(option + " " + path + ": is the " + input_name +
                         "; expected an output that does not replace an input");
    for (std::size_t j = 0; j < i; ++j)
      if (!outputs[j].second.empty() && identity(path) == identity(outputs[j].second))
        throw InputError(option + " " + path + ": the same file as " + outputs[j].first +
                         "; expected a different file for each output");
  }
}

void check_parameter_range(const ModelSpec& spec, const std::string& parameter,
                           const std::vector<double>& values, const std::string& where) {
  for (double v : values) {
    ModelSpec at = spec;
    at.set(parameter, v);
    const auto problems = at.problems();
    if (!problems.empty())
      throw InputError(where + parameter + " = " + format_double(v) + " is outside the model's " +
                       "domain: " + problems.front().first + " must be " + problems.front().second);
  }
}

void check_options(const OptionCheck& problem, const std::string& where) {
  if (!problem) return;
  // The command line's names of the options fields it sets (the study file's keys are the same
  // without the dashes, where = "FILE: branches[i]."); a field it does not set keeps its own name.
  static const std::pair<const char*, const char*> names[] = {
      {"initial_step", "step"},
      {"max_step", "max-step"},
      {"max_points", "max-points"},
      {"orbit.transient", "transient"},
      {"transient", "transient"},
      {"orbit.shooting.segments", "segments"},
      {"shooting.segments", "segments"},
      {"rtol", "rtol"},
      {"atol", "atol"},
      {"orbit.shooting.flow.rtol", "rtol"},
      {"orbit.shooting.flow.atol", "atol"},
      {"shooting.flow.rtol", "rtol"},
      {"shooting.flow.atol", "atol"}};
  std::string name = problem->field;
  for (const auto& [field, option] : names)
    if (name == field) {
      name = option;
      break;
    }
  if (where.empty()) {
    throw InputError("--" + name + ": expected " + problem->expected);
  }
  std::replace(name.begin(), name.end(), '-', '_');
  throw InputError(where + name + ": expected " + problem->expected);
}

}  // namespace sympathy::cli
