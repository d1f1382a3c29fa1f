#include "sympathy/continuation/predictor.hpp"

#include <cmath>

namespace sympathy {

Eigen::VectorXd predict(const BranchSpace& space, const ContinuationPoint* before,
                        const ContinuationPoint& a, double ds, bool curved, double min_cosine) {
  const int N = space.unknowns();
  Eigen::VectorXd ya(N + 1);
  ya << a.unknowns, a.parameter;
  Eigen::VectorXd guess = ya + ds * a.tangent;
  if (!curved || !before || before->section.size() != a.section.size() ||
      before->section != a.section)
    return guess;
  Eigen::VectorXd y0(N + 1);
  y0 << before->unknowns, before->parameter;
  const double h = std::sqrt(space.dot(ya - y0, ya - y0));  // chord length from before to a
  if (!(h > 0.0) || ds > 3.0 * h) return guess;
  // Y(s) = ya + s t1 + c2 s^2 + c3 s^3 with Y(-h) = y0, Y'(-h) = t0 (tangents in the current
  // scaled norm; the previous one renormalized there).
  const Eigen::VectorXd& t1 = a.tangent;
  const Eigen::VectorXd t0 =
      before->tangent / std::sqrt(space.dot(before->tangent, before->tangent));
  if (space.dot(t0, t1) < min_cosine) return guess;
  const Eigen::VectorXd D = y0 - ya + h * t1, E = t0 - t1;
  const Eigen::VectorXd c2 = (3.0 * D / h + E) / h;
  const Eigen::VectorXd c3 = (c2 * h * h - D) / (h * h * h);
  return guess + ds * ds * (c2 + ds * c3);
}

}  // namespace sympathy
