#include "sympathy/continuation/driver.hpp"

#include <cmath>

namespace sympathy {

std::string to_string(StopReason s) {
  switch (s) {
    case StopReason::ParameterBound:
      return "parameter bound";
    case StopReason::PointLimit:
      return "point limit";
    case StopReason::MinimumStep:
      return "minimum step";
    case StopReason::Interrupted:
      return "interrupted";
    case StopReason::StartFailed:
      return "start failed";
    case StopReason::TurnedBack:
      return "turned back";
    case StopReason::HopfPoint:
      return "Hopf point";
    case StopReason::Homoclinic:
      return "homoclinic orbit";
    case StopReason::Closed:
      return "closed";
    case StopReason::UserValue:
      return "user value";
    case StopReason::Nonsmooth:
      return "grazing";
  }
  return "?";
}

}  // namespace sympathy

namespace sympathy::driver {

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
