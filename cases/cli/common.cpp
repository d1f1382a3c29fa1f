#include "cases/cli/common.hpp"

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
  if (!(o.rtol > 0.0 && o.rtol < 1.0)) throw InputError("--rtol: expected a number in (0, 1)");
  if (!(o.atol > 0.0)) throw InputError("--atol: expected a positive number");
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

}  // namespace sympathy::cli
