// The stiffness of a guess's period for OrbitOptions::switch_when_stiff (private to continuation:
// solve_periodic_orbit, find_periodic_orbit and Continuation measure it the same way).
#pragma once

#include <optional>

#include "sympathy/core/stiffness.hpp"

namespace sympathy {

// measure_stiffness over [0, period] from z0, or nullopt where the guess cannot be integrated:
// the method then stays as set, and Newton's own integrations say what fails.
inline std::optional<StiffnessEstimate> stiffness_of_guess(const OdeSystem& system,
                                                           const FlowOptions& flow,
                                                           const Eigen::VectorXd& z0,
                                                           const ParameterValues& p,
                                                           double period) {
  try {
    return measure_stiffness(system, flow, z0, p, 0.0, period);
  } catch (const IntegrationError&) {
    return std::nullopt;
  }
}

}  // namespace sympathy
