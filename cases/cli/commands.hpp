// The subcommands of the sympathy executable.
#pragma once

#include <string>
#include <vector>

namespace sympathy::cli {

int run_simulate(const std::vector<std::string>& args);
int run_orbit(const std::vector<std::string>& args);
int run_continue(const std::vector<std::string>& args);
int run_equilibria(const std::vector<std::string>& args);
int run_curve(const std::vector<std::string>& args);
int run_map(const std::vector<std::string>& args);
int run_study(const std::vector<std::string>& args);
int run_fit(const std::vector<std::string>& args);
int run_basins(const std::vector<std::string>& args);
int run_sweep(const std::vector<std::string>& args);

}  // namespace sympathy::cli

namespace sympathy::bench {

// sympathy bench (cases/bench/bench.cpp).
int run_bench(const std::vector<std::string>& args);

}  // namespace sympathy::bench
