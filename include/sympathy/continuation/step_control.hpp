// Step control of an orbit branch beyond the driver's step rule (driver.hpp): a step is bounded
// in the parameter, and aimed so that a multiplier near the unit circle moves less than a set
// amount of modulus (a narrow window of instability is then not stepped over) and the pairing
// of multipliers stays unambiguous. The limits grow with the
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

}  // namespace sympathy
