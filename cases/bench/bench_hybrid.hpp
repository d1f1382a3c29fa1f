// sympathy bench, section (l): the paper's impulsive escapement (eq. 2, a hybrid system: the flow
// restarts at each switching-surface crossing and carries the sensitivities across by saltation
// matrices) against the smoothed one (eq. 3, eps = 0.05, the turning-point pulse resolved by step
// caps) at equal error, each model against its own reference.
#pragma once

#include <ostream>
#include <string>

#include "sympathy/core/csv.hpp"

namespace sympathy::bench {

// The row setup's anti-phase orbit at Table II and in-phase orbit at Table III (cases/row2.toml),
// each on both escapements, over tolerance sweeps of the default preset's integrator (Adams on
// the augmented system) and of Dormand-Prince: the errors of the period, the multipliers and the
// trivial multiplier against the model's own reference (BDF rtol 1e-13), and the cost of one
// period with the monodromy at the solved orbit (CPU seconds, median of a few runs, and steps);
// then the cost per period each model needs to reach a stated error, interpolated between the
// settings, and the ratio hybrid / smoothed. Rows go to `csv` (bench.csv's columns), tables to
// `md`. `quick`: four tolerances of Adams only. `root`: where cases/ is.
void bench_hybrid(const std::string& root, bool quick, CsvWriter& csv, std::ostream& md);

}  // namespace sympathy::bench
