// sympathy bench, section (g): the synchronized orbit of N identical metronomes with all its
// multipliers, computed in the symmetry reduction and on the whole state.
#pragma once

#include <ostream>
#include <string>

namespace sympathy::bench {

// Runs the section on cases/row2.toml and cases/row/rowN.toml (N = 4, 8, 64; 4 and 8 with
// `quick`), writes `out`/identical.csv and appends its table to `md`. `root`: where cases/ is.
void bench_identical(const std::string& root, const std::string& out, bool quick, std::ostream& md);

}  // namespace sympathy::bench
