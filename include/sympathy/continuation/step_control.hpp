// Step control of a continuation run. Steps grow after easy corrections and shrink after hard or
// failed ones; a step is also bounded in the parameter, and aimed so that a multiplier near the
// unit circle moves less than a set amount of modulus (a narrow window of instability is then
// not stepped over) and the pairing of multipliers stays unambiguous. The limits grow with the
// step at the rates just seen: the modulus change like ds, a pairing error like ds^2.
#pragma once

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/multiplier_tracking.hpp"

namespace sympathy {

// The step ds limited so that the parameter moves at most max_parameter_step (at rate dp_per_ds).
double parameter_limited_step(double ds, double dp_per_ds, const ContinuationOptions& options);

struct MultiplierMotion {
  bool too_far = false;  // the step must be retried shorter
  double aim = 0.0;      // the step that keeps both limits (infinite: no limit)
};
// How the multipliers moved over a step of length ds.
MultiplierMotion multiplier_motion(const TrackedMultipliers& tracked, double ds,
                                   const ContinuationOptions& options);

// The next step after a point accepted with `iterations` corrector iterations; `after_retry`:
// that point came from a step retried shorter because the multipliers moved too far, and the step
// grows by at most 1.2 instead of 1.5 (near a branch point the multipliers' motion grows faster
// than the step: on the anti-phase k-branch a step grown 1.5 times after a retry was retried
// again at least 8 times of its 15 retries; at 1.2, 8 retries and 65 points instead of 15 and
// 70, 13% less time).
double next_step(double ds, int iterations, double aim, const ContinuationOptions& options,
                 bool after_retry = false);

}  // namespace sympathy
