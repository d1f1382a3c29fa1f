// Broyden's ("good") quasi-Newton method without forming its matrices.
//
// B_(k+1) = B_k + (y_k - B_k s_k) <s_k, .> / <s_k, s_k>, with s_k the step taken and y_k the
// change of the residual, in an inner product <., .>. When every step is the full quasi-Newton
// step s_k = -B_k^-1 F(x_k), the updates need no matrix: s_k follows from z = -B_0^-1 F(x_k) and
// the earlier steps alone (C. T. Kelley, Iterative Methods for Linear and Nonlinear Equations,
// SIAM 1995, sec. 7.3), so B_0 is only ever solved with.
#pragma once

#include <optional>
#include <vector>

#include <Eigen/Dense>

namespace sympathy {

// The step -B_k^-1 F(x_k) from z = -B_0^-1 F(x_k) and the steps s_0 .. s_(k-1) taken so far;
// nothing where the last update is nearly singular (the step would blow up).
template <class Dot>
std::optional<Eigen::VectorXd> broyden_step(Eigen::VectorXd z,
                                            const std::vector<Eigen::VectorXd>& steps,
                                            const Dot& dot) {
  for (std::size_t j = 0; j + 1 < steps.size(); ++j)
    z += dot(steps[j], z) / dot(steps[j], steps[j]) * steps[j + 1];
  if (!steps.empty()) {
    const double denominator = 1.0 - dot(steps.back(), z) / dot(steps.back(), steps.back());
    if (!(std::abs(denominator) > 0.1)) return std::nullopt;
    z /= denominator;
  }
  return z;
}

}  // namespace sympathy
