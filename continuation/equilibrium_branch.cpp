#include "sympathy/continuation/equilibrium_branch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "equilibrium_continuation.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

OptionCheck EquilibriumOptions::validate() const {
  // The steps, their point limit and the turn: the driver's own checks.
  if (auto wrong = driver::step_options(*this).validate()) return wrong;
  if (max_iterations < 2 || max_iterations > 50)
    return OptionProblem{"max_iterations", "an integer from 2 to 50"};
  if (!positive(tolerance) || tolerance >= 1e-3)
    return OptionProblem{"tolerance", "a positive number below 1e-3"};
  if (!positive(state_scale_floor)) return OptionProblem{"state_scale_floor", "a positive number"};
  if (!positive(location_tolerance) || location_tolerance >= 0.1)
    return OptionProblem{"location_tolerance", "a positive number below 0.1"};
  for (double v : user_points)
    if (!std::isfinite(v)) return OptionProblem{"user_points", "finite parameter values"};
  return std::nullopt;
}

std::string to_string(EquilibriumEventType t) {
  switch (t) {
    case EquilibriumEventType::Fold:
      return "LP";
    case EquilibriumEventType::BranchPoint:
      return "BP";
    case EquilibriumEventType::Hopf:
      return "HB";
    case EquilibriumEventType::UserPoint:
      return "UZ";
  }
  return "?";
}

std::string EquilibriumProblem::problem_with(const OdeSystem& system) const {
  if (parameter < 0 || parameter >= system.parameter_count())
    return "parameter: expected the index of a named parameter";
  if (values.size() != system.parameter_values_size())
    return "values: expected " + std::to_string(system.parameter_values_size()) + " values";
  if (!std::isfinite(from) || !std::isfinite(to) || from == to)
    return "from, to: expected two different finite values";
  if (at && !(*at > std::min(from, to) && *at < std::max(from, to)))
    return "at " + format_double(*at) + ": expected a value strictly between from and to";
  if (start_state.size() != system.dimension())
    return "start_state: expected " + std::to_string(system.dimension()) + " values";
  if (auto wrong = newton.validate()) return "newton." + wrong->message();
  return "";
}

EquilibriumBranch continue_equilibria(const OdeSystem& system, const EquilibriumProblem& problem,
                                      EquilibriumOptions options,
                                      const EquilibriumCallbacks& callbacks) {
  const Stopwatch started;
  if (const std::string wrong = problem.problem_with(system); !wrong.empty())
    throw std::invalid_argument("equilibria: " + wrong);
  options.lower = std::min(problem.from, problem.to);
  options.upper = std::max(problem.from, problem.to);
  if (auto wrong = options.validate())
    throw std::invalid_argument("equilibria: " + wrong->message());
  EquilibriumBranch branch;
  branch.parameter = problem.parameter;
  branch.parameter_name = system.parameter_names()[problem.parameter];
  branch.state_names = system.state_names();
  branch.options = options;
  const double first = problem.first_value();
  branch.start_values = system.with_parameter(problem.values, problem.parameter, first);
  const Equilibrium start =
      solve_equilibrium(system, branch.start_values, problem.start_state, problem.newton);
  if (!start.converged) {
    branch.stop = StopReason::StartFailed;
    branch.stop_reason = "no equilibrium near the start at " + branch.parameter_name + " = " +
                         format_double(first) + ": " + start.reason;
    branch.seconds = started.seconds();
    return branch;
  }
  using Driver = driver::Callbacks<EquilibriumPoint, EquilibriumEvent>;
  auto one_way = [&](double to, const Driver& cb) {
    detail::EquilibriumContinuation run(system, problem.parameter, branch.start_values, options);
    EquilibriumPoint first_point = run.start(start, to > first ? 1 : -1);
    return driver::continuation(run, std::move(first_point),
                                detail::equilibrium_driver_options(options), cb);
  };
  Driver forward_callbacks{callbacks.on_point, callbacks.on_event, {}, callbacks.stop_requested};
  driver::Result<EquilibriumPoint, EquilibriumEvent> result;
  if (!problem.at) {
    result = one_way(problem.to, forward_callbacks);
  } else {
    // Backward first, reported as it comes with negative indices, then forward.
    Driver back = forward_callbacks;
    if (callbacks.on_point)
      back.on_point = [&](const EquilibriumPoint& pt) {
        if (pt.index == 0) return;  // the start is reported once, by the forward run
        EquilibriumPoint q = pt;
        q.index = -pt.index;
        callbacks.on_point(q);
      };
    auto backward = one_way(problem.from, back);
    result = driver::join(std::move(backward), one_way(problem.to, forward_callbacks));
  }
  branch.points = std::move(result.points);
  branch.events = std::move(result.events);
  branch.stop = result.stop;
  branch.stop_reason = std::move(result.message);
  branch.seconds = started.seconds();
  return branch;
}

}  // namespace sympathy
