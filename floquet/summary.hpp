// Shared by the analyses of floquet/: the multipliers ordered, and what is read off them.
#pragma once

#include "sympathy/floquet/floquet.hpp"

namespace sympathy {

// Orders a.multipliers by decreasing modulus (conjugate pairs positive argument first), then
// summarizes.
void order_and_summarize(FloquetAnalysis& a, const FloquetOptions& options);
// Sets the trivial multiplier's index and error, the largest other modulus, the count of unstable
// ones and the stability, from a.multipliers.
void summarize(FloquetAnalysis& a, const FloquetOptions& options);

}  // namespace sympathy
