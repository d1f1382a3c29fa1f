#include "sympathy/continuation/driver.hpp"

#include <cmath>

namespace sympathy::driver {

std::string to_string(Stop s) {
  switch (s) {
    case Stop::Bound:
      return "bound";
    case Stop::PointLimit:
      return "point limit";
    case Stop::MinimumStep:
      return "minimum step";
    case Stop::Interrupted:
      return "interrupted";
    case Stop::StartFailed:
      return "start failed";
    case Stop::ProblemEnd:
      return "problem end";
    case Stop::Closed:
      return "closed";
  }
  return "?";
}

OptionCheck Options::validate() const {
  if (!positive(min_step)) return OptionProblem{"min_step", "a positive number"};
  if (!(positive(initial_step) && initial_step >= min_step))
    return OptionProblem{"initial_step", "a positive number, at least the minimum step"};
  if (!(std::isfinite(max_step) && max_step >= initial_step))
    return OptionProblem{"max_step", "a number at least the initial step"};
  if (max_points < 2) return OptionProblem{"max_points", "an integer of at least 2"};
  if (!(min_tangent_cosine > 0.0 && min_tangent_cosine < 1.0))
    return OptionProblem{"min_tangent_cosine", "a number in (0, 1)"};
  if (location_retries < 0) return OptionProblem{"location_retries", "a non-negative integer"};
  if (!(rule.growth >= 1.0 && rule.growth_after_screen >= 1.0 && rule.shrink > 0.0 &&
        rule.shrink <= 1.0 && rule.fast_iterations < rule.slow_iterations))
    return OptionProblem{"rule", "growths of at least 1, a shrink in (0, 1], fast below slow"};
  return std::nullopt;
}

}  // namespace sympathy::driver
