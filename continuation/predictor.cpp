#include "sympathy/continuation/predictor.hpp"

#include <cmath>

namespace sympathy {

Eigen::VectorXd predict(const BranchSpace& space, const ContinuationPoint* before,
                        const ContinuationPoint& a, double ds, bool curved, double min_cosine) {
  const int N = space.unknowns();
  Eigen::VectorXd ya(N + 1);
  ya << a.unknowns, a.parameter;
  Eigen::VectorXd guess = ya + ds * a.tangent;
  if (!curved || !before || !(before->section == a.section)) return guess;
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

std::optional<BetweenGuess> predict_between(const BranchSpace& space, const ContinuationPoint& a,
                                            const ContinuationPoint& b, double s,
                                            double min_cosine) {
  const int N = space.unknowns();
  if (!(b.section == a.section)) return std::nullopt;
  Eigen::VectorXd ya(N + 1), yb(N + 1);
  ya << a.unknowns, a.parameter;
  yb << b.unknowns, b.parameter;
  const Eigen::VectorXd D = yb - ya;
  const double h = std::sqrt(space.dot(D, D));
  if (!(h > 0.0)) return std::nullopt;
  const Eigen::VectorXd ta = a.tangent / std::sqrt(space.dot(a.tangent, a.tangent));
  const Eigen::VectorXd tb = b.tangent / std::sqrt(space.dot(b.tangent, b.tangent));
  if (space.dot(ta, tb) < min_cosine) return std::nullopt;
  // Y(u) = ya + u ta + c2 u^2 + c3 u^3 with Y(h) = yb, Y'(h) = tb.
  const Eigen::VectorXd P = D - h * ta, Q = tb - ta;
  const Eigen::VectorXd c2 = (3.0 * P - h * Q) / (h * h);
  const Eigen::VectorXd c3 = (h * Q - 2.0 * P) / (h * h * h);
  // Its arclength along a's tangent, as the corrector measures it: a cubic in u, increasing from
  // 0 at u = 0 to about b.step at u = h; bisection for where it is s.
  const double e1 = space.dot(a.tangent, ta), e2 = space.dot(a.tangent, c2),
               e3 = space.dot(a.tangent, c3);
  auto along = [&](double u) { return u * (e1 + u * (e2 + u * e3)); };
  if (!(along(h) > s)) return std::nullopt;
  double lo = 0.0, hi = h;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (along(mid) < s ? lo : hi) = mid;
  }
  const double u = 0.5 * (lo + hi);
  return BetweenGuess{ya + u * ta + u * u * (c2 + u * c3), u / h};
}

}  // namespace sympathy
