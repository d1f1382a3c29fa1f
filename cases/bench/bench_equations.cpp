// Section (h) of sympathy bench. Each timing is the median of five runs of N calls (N = 2e6
// right-hand sides, 2e5 Jacobians; a tenth with --quick) over 64 states spread over the
// attractor's size, through the virtual OdeSystem interface for both systems; the generated
// system is compiled in a fresh temporary cache (removed afterwards), so the user's cache is
// neither used nor written.
#include "cases/bench/bench_equations.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <random>
#include <vector>

#include "cases/bench/hand_written_systems.hpp"
#include "cases/cli/common.hpp"
#include "sympathy/cases/equation_compiler.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// Seconds per call of f over `states`, the median of five runs of `calls` calls.
template <class F>
double per_call(const std::vector<Eigen::VectorXd>& states, long calls, F&& f) {
  std::vector<double> runs;
  for (int r = 0; r < 5; ++r) {
    const Stopwatch clock;
    for (long i = 0; i < calls; ++i) f(states[static_cast<std::size_t>(i) % states.size()]);
    runs.push_back(clock.seconds() / static_cast<double>(calls));
  }
  return median(runs);
}

struct Row {
  std::string system, what;
  double hand = 0.0, generated = 0.0;  // seconds per call (or per orbit)
};

template <class Hand>
void compare(const std::string& name, const EquationCase& file, const std::string& cache,
             bool quick, double scale, std::vector<Row>& rows) {
  const Eigen::VectorXd p = file.parameter_values();
  const auto build = build_equation_system(file, p, cache);
  const OdeSystem& generated = *build.system;
  const Hand hand_system(p);
  const OdeSystem& hand = hand_system;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<Eigen::VectorXd> states;
  for (int k = 0; k < 64; ++k) {
    Eigen::VectorXd z(generated.dimension());
    for (int i = 0; i < z.size(); ++i) z[i] = scale * u(rng);
    states.push_back(z);
  }
  Eigen::VectorXd dz(generated.dimension());
  Eigen::MatrixXd jac;
  double sink = 0.0;
  const long rhs_calls = quick ? 200000 : 2000000, jac_calls = rhs_calls / 10;
  auto rhs = [&](const OdeSystem& s) {
    return per_call(states, rhs_calls, [&](const Eigen::VectorXd& z) {
      s.rhs(0.0, z.data(), p.data(), dz.data());
      sink += dz[0];
    });
  };
  auto jacobian = [&](const OdeSystem& s) {
    return per_call(states, jac_calls, [&](const Eigen::VectorXd& z) {
      s.jacobian(0.0, z.data(), p.data(), jac);
      sink += jac(0, 0);
    });
  };
  rows.push_back({name, "rhs", rhs(hand), rhs(generated)});
  rows.push_back({name, "Jacobian", jacobian(hand), jacobian(generated)});
  if (sink == 1.2345) std::printf(" ");  // keep the calls
}

}  // namespace

void bench_equations(const std::string& root, bool quick, std::ostream& md) {
  const std::string dir = root + "cases/examples/";
  const auto cache = std::filesystem::temp_directory_path() /
                     ("sympathy_bench_equations_" + std::to_string(::getpid()));
  std::filesystem::remove_all(cache);
  std::vector<Row> rows;

  // Compile time: the Lorenz system into the fresh cache, then again from it.
  const EquationCase lrz = EquationCase::load(dir + "lrz.toml");
  const auto first = build_equation_system(lrz, lrz.parameter_values(), cache.string());
  const auto second = build_equation_system(lrz, lrz.parameter_values(), cache.string());
  std::printf("(h) lrz: compiled in %.2f s, from the cache in %.4f s\n", first.seconds,
              second.seconds);

  compare<HandHopf>("hopf", EquationCase::load(dir + "hopf.toml"), cache.string(), quick, 1.0,
                    rows);
  compare<HandLorenz>("lrz", lrz, cache.string(), quick, 20.0, rows);
  compare<HandAbc>("abc", EquationCase::load(dir + "abc.toml"), cache.string(), quick, 0.5, rows);

  // A whole orbit: the Hopf circle from the file's start, at the library's defaults.
  {
    const EquationCase hopf = EquationCase::load(dir + "hopf.toml");
    const Eigen::VectorXd p = hopf.parameter_values();
    const auto build = build_equation_system(hopf, p, cache.string());
    const HandHopf hand(p);
    auto orbit_time = [&](const OdeSystem& s) {
      std::vector<double> runs;
      for (int r = 0; r < 5; ++r) {
        const Stopwatch clock;
        find_periodic_orbit(s, p, hopf.initial_state(nullptr), InvariantSubspace(), OrbitOptions{});
        runs.push_back(clock.seconds());
      }
      return median(runs);
    };
    rows.push_back(
        {"hopf", "orbit (find_periodic_orbit)", orbit_time(hand), orbit_time(*build.system)});
  }
  std::filesystem::remove_all(cache);

  md << "\n## (h) Equation case files: generated against hand-written\n\n"
     << "Compile time of cases/examples/lrz.toml: " << format_number(first.seconds)
     << " s the first time, " << format_number(second.seconds) << " s from the cache.\n\n"
     << "| system | what | hand-written | generated | generated / hand |\n"
     << "|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const bool orbit = r.what.rfind("orbit", 0) == 0;
    const double unit = orbit ? 1.0 : 1e9;
    const char* label = orbit ? " s" : " ns";
    char line[256];
    std::snprintf(line, sizeof line, "| %s | %s | %.3g%s | %.3g%s | %.2f |\n", r.system.c_str(),
                  r.what.c_str(), r.hand * unit, label, r.generated * unit, label,
                  r.generated / r.hand);
    md << line;
    std::printf("(h) %-5s %-28s hand %.3g%s  generated %.3g%s  ratio %.2f\n", r.system.c_str(),
                r.what.c_str(), r.hand * unit, label, r.generated * unit, label,
                r.generated / r.hand);
  }
  std::fflush(stdout);
}

}  // namespace sympathy::bench
