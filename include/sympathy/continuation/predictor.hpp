// The predictor of a continuation step: along the tangent at the last point a, or, when the point
// before a shares a's phase section (the unknowns then lie on one smooth curve), along the cubic
// through both points with their tangents. Its error is O(ds^3) instead of O(ds^2): one corrector
// iteration fewer per point (tested on the fold normal form).
#pragma once

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/branch_space.hpp"

namespace sympathy {

// The guess for the point at arclength ds from a; `before` may be null. `curved`: the cubic where
// it applies; `min_cosine`: tangents turning more than this between the two points fall back to
// the straight predictor.
Eigen::VectorXd predict(const BranchSpace& space, const ContinuationPoint* before,
                        const ContinuationPoint& a, double ds, bool curved, double min_cosine);

}  // namespace sympathy
