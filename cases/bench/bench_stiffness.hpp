// sympathy bench, section (j): the integrator chosen by the measured stiffness, against each
// integrator forced, on platforms from the paper's to a stiff one.
#pragma once

#include <ostream>
#include <string>

namespace sympathy::bench {

// The row setup's in-phase orbit (cases/row2.toml, as `sympathy orbit --start in-phase` finds
// it) at four platforms, with the default preset as it runs (the stiffness measured, the method
// chosen) and with Adams and BDF forced; writes `out`/stiffness.csv and appends its table to
// `md`. `quick`: one run each, and forced Adams skipped where it takes seconds (k = 1e6 N/m,
// c = 5000 N s/m). `root`: where cases/ is.
void bench_stiffness(const std::string& root, const std::string& out, bool quick, std::ostream& md);

}  // namespace sympathy::bench
