// sympathy bench, section (i): the paper's Fig. 8 study from its file, as `sympathy study` runs it.
#pragma once

#include <ostream>
#include <string>

namespace sympathy::bench {

// Runs cases/figures/fig08.toml (both branches side by side, starts included, the default
// preset) three times (once with `quick`), its outputs under `out`/study, writes
// `out`/study.csv and appends its table to `md`. `root`: where cases/ is.
void bench_study(const std::string& root, const std::string& out, bool quick, std::ostream& md);

}  // namespace sympathy::bench
