// sympathy bench, section (k): basin runs stopped when their fate is known (`basins
// --early-stop`), against full-length runs of the same starts.
#pragma once

#include <ostream>
#include <string>

namespace sympathy::bench {

// Per case (the row setup at Table II, k = 20, 40, 47.5, 50, 55, 60, 80 N/m, and Table III; with
// `quick` k = 60 and Table III alone): 200 starts (32 with `quick`) run full-length (300 s; 100
// s with `quick`) with BDF at rtol 1e-8, then stopped early with BDF and with ERK at rtol 1e-6,
// each on one thread, the candidate orbits' computation included. Reports the runs per second,
// the agreement of the classes and times to synchronize with the full runs, and how long after
// its time to synchronize each run stopped; writes `out`/basins.csv and appends its table to
// `md`. `root`: where cases/ is.
void bench_basins(const std::string& root, const std::string& out, bool quick, std::ostream& md);

}  // namespace sympathy::bench
