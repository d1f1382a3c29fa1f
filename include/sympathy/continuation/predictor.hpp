// The predictor of a continuation step: along the tangent at the last point a, or, when the point
// before a shares a's phase section (the unknowns then lie on one smooth curve), along the cubic
// through both points with their tangents. Its error is O(ds^3) instead of O(ds^2): one corrector
// iteration fewer per point (tested on the fold normal form).
#pragma once

#include <optional>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/branch_space.hpp"

namespace sympathy {

// The guess for the point at arclength ds from a; `before` may be null. `curved`: the cubic where
// it applies; `min_cosine`: tangents turning more than this between the two points fall back to
// the straight predictor.
Eigen::VectorXd predict(const BranchSpace& space, const ContinuationPoint* before,
                        const ContinuationPoint& a, double ds, bool curved, double min_cosine);

// Inside a step, for location: the guess for the point at arclength s from a (along a's tangent,
// 0 < s < b.step) on the cubic through a and b with their tangents (b corrected in a's section,
// its tangent in that section too), and how far along the cubic it lies (0 at a, 1 at b); nullopt
// where the tangents turn more than `min_cosine` allows or the cubic does not reach s. Its error
// is O(h^4) in the step h, where a's tangent alone gives O(h^2): on the in-phase k-branch's NS
// pair the straight guesses were 0.03-0.08 off in k and each probe took three runs with
// sensitivities.
struct BetweenGuess {
  Eigen::VectorXd y;
  double fraction = 0.0;
};
std::optional<BetweenGuess> predict_between(const BranchSpace& space, const ContinuationPoint& a,
                                            const ContinuationPoint& b, double s,
                                            double min_cosine);

}  // namespace sympathy
