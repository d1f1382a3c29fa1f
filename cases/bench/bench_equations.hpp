// sympathy bench, section (h): equation case files, generated against hand-written.
#pragma once

#include <ostream>
#include <string>

namespace sympathy::bench {

// The right-hand side and Jacobian of cases/examples/{hopf,lrz,abc}.toml compiled from the file
// against the same systems written by hand in C++ (time per call, through OdeSystem as the engine
// calls them), the Hopf orbit found by each, and the compile time of one system in a fresh cache
// against taking it from the cache. Writes its table to `md`. `root`: where cases/ is.
void bench_equations(const std::string& root, bool quick, std::ostream& md);

}  // namespace sympathy::bench
