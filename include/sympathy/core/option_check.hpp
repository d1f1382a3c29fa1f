// What is wrong with an options value, in the manner of ceres' Solver::Options::IsValid: each
// options struct owns its defaults (default member initializers, one place each) and a
// validate() that names the first field out of its domain and what was expected. The library
// checks options with it before any work; the command line and study files call the same one and
// translate the field's name into their own option or key (OptionProblem::field is a path such
// as "orbit.shooting.flow.rtol").
#pragma once

#include <cmath>
#include <optional>
#include <string>

namespace sympathy {

struct OptionProblem {
  std::string field;     // e.g. "initial_step", or "orbit.transient" for a nested one
  std::string expected;  // e.g. "a positive number"
  std::string message() const { return field + ": expected " + expected; }
};

using OptionCheck = std::optional<OptionProblem>;

// The problem of a nested options value with its field names under `prefix` ("orbit.").
inline OptionCheck nested(const std::string& prefix, OptionCheck problem) {
  if (problem) problem->field = prefix + problem->field;
  return problem;
}

inline bool positive(double v) {
  return std::isfinite(v) && v > 0.0;
}
inline bool non_negative(double v) {
  return std::isfinite(v) && v >= 0.0;
}

}  // namespace sympathy
