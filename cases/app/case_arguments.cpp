#include "cases/app/case_arguments.hpp"

#include <algorithm>
#include <string>
#include <thread>

#include "cases/app/equilibrium_curve_run.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/start_data.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy::app {

LoadedCase load_case(const Arguments& args) {
  return load_case(args.positional(0), args.text("--params", ""), args.assignments("--set"));
}

LoadedEquations load_equations(const Arguments& args) {
  return load_equations(args.positional(0), args.text("--params", ""), args.assignments("--set"),
                        start_data_path(args));
}

LoadedSystem load_system(const Arguments& args) {
  const auto period = data_period(args);  // checked before anything is compiled
  // A saved orbit for the orbit commands; equilibria read their saved point in their request.
  // A Hopf curve's point is no orbit: continue reads it in its request (the family born there).
  std::optional<SavedStart> saved =
      args.command() == "equilibria" ? std::nullopt : saved_start(args);
  if (saved && holds_hopf_curve(saved->path)) saved.reset();
  // What the model must allow (a piecewise-smooth one: orbits and what is built on them); a curve
  // of equilibria is equilibria.
  const std::string what =
      args.command() == "curve" && wants_equilibrium_curve(args) ? "equilibria" : args.command();
  LoadedSystem c(args.positional(0), args.text("--params", ""), args.assignments("--set"),
                 start_data_path(args), what, saved);
  if (period) c.scale_data_time(*period);
  return c;
}

ParameterWindow parameter_window(const Arguments& args, const LoadedSystem& c) {
  for (const char* required : {"--param", "--from", "--to"})
    if (!args.has(required)) throw InputError(std::string(required) + " is required");
  ParameterWindow w;
  w.parameter = *args.value("--param");
  c.require_parameter("--param", w.parameter);
  w.from = args.number("--from", 0.0);
  w.to = args.number("--to", 0.0);
  if (w.from == w.to) throw InputError("--from and --to: expected different values");
  if (args.has("--at")) w.at = args.number("--at", 0.0);
  return w;
}

Accuracy accuracy(const Arguments& args) {
  const auto text = args.value("--accuracy");
  return text ? parse_accuracy(*text, "--accuracy") : Accuracy::Default;
}

FlowOptions flow_options(const Arguments& args, FlowOptions o) {
  o.rtol = args.number("--rtol", o.rtol);
  o.atol = args.number("--atol", o.atol);
  const char* given = o.method == Method::BDF ? "bdf" : o.method == Method::Adams ? "adams" : "erk";
  const std::string method = args.text("--method", given);
  if (method == "bdf") {
    o.method = Method::BDF;
    o.nonlinear_solver = NonlinearSolver::Newton;
  } else if (method == "adams") {
    o.method = Method::Adams;
    o.nonlinear_solver = NonlinearSolver::FixedPoint;
  } else if (method == "erk") {
    o.method = Method::ERK;
    o.sensitivities = Sensitivities::Augmented;  // an explicit method has no sensitivity module
  } else {
    throw InputError("--method " + method + ": expected bdf, adams or erk");
  }
  if (auto sensitivities = args.value("--sensitivities")) {
    if (*sensitivities == "forward")
      o.sensitivities = Sensitivities::ForwardModule;
    else if (*sensitivities == "augmented")
      o.sensitivities = Sensitivities::Augmented;
    else
      throw InputError("--sensitivities " + *sensitivities + ": expected forward or augmented");
  }
  check_options(o.validate(), "");
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

int segment_threads(const Arguments& args) {
  // Checked with the rest by ShootingOptions::validate (check_options names it --threads).
  if (args.has("--threads")) return args.integer("--threads", 1);
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 256);
}

void shooting_flow_options(const Arguments& args, OrbitOptions& o) {
  o.shooting.flow = flow_options(args, o.shooting.flow);
  o.transient_flow.linear_solver = o.shooting.flow.linear_solver;
  if (args.has("--method")) o.switch_when_stiff = false;  // the method asked for, stiff or not
}

}  // namespace sympathy::app
