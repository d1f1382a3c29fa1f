// Bench section (f): the row setup's anti-phase k-branch, k = 1 to 100 N/m, as `sympathy continue`
// runs it (start and transient included), per accuracy preset and per integrator at a few
// tolerances: the largest relative error of the located events (BP, NS, NS) against a reference
// at rtol 1e-13 (BDF) against the whole run's time, with AUTO-07p's measured points
// (bench/anchors/auto07p_row_k.csv) beside them, labelled as AUTO's.
#pragma once

#include <ostream>
#include <string>

#include "sympathy/core/csv.hpp"

namespace sympathy::bench {

// Rows go to `csv` (bench.csv's columns) and a table to `md`; `root` is where cases/ and bench/
// are ("" or the source directory).
void bench_branch_accuracy(const std::string& root, bool quick, CsvWriter& csv, std::ostream& md);

}  // namespace sympathy::bench
