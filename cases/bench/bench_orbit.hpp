// What the bench's orbit sections share: an integrator setting, one orbit solved by Newton from a
// guess at that setting with what it cost, the multipliers' error against a reference's, the
// timing of repeated runs, and bench.csv's columns with the row of one solved orbit. Sections
// (a)-(c) (bench.cpp) and (l) (bench_hybrid.cpp) measure with the same pieces, so their numbers
// compare.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <ctime>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::bench {

struct Setting {
  std::string name;
  FlowOptions flow;
  int segments = 1;
};

struct Result {
  bool converged = false;
  double period = 0.0;
  Eigen::VectorXd state0;                         // the orbit's initial state
  std::vector<std::complex<double>> multipliers;  // nontrivial
  double trivial_error = NAN;
  double parameter = 0.0;  // (c): the located branch point
  double seconds = 0.0;
  FlowStatistics flow;
  int iterations = 0;
  std::string note;
};

// The shooting flow at `rtol` (atol 1e-2 rtol) with `method` (Newton with BDF, fixed point
// otherwise), on the forward-sensitivity module unless changed after.
Setting setting(const std::string& name, Method method, double rtol, int segments = 1,
                LinearSolver solver = LinearSolver::Dense,
                Derivatives derivatives = Derivatives::Model, bool resolve = true);

// The references every orbit section measures against: BDF at rtol 1e-13, the pulse resolved,
// and the same at 1e-12, whose change from it is the level below which errors are not resolved.
Setting reference_setting();
Setting check_setting();

OrbitOptions orbit_options(const Setting& s);

// Largest distance between the multipliers and the reference's, paired by least total squared
// distance.
double multiplier_error(const std::vector<std::complex<double>>& a,
                        const std::vector<std::complex<double>>& b);

// The guess every setting starts from: the orbit from `start` (find_periodic_orbit at the
// library's options) with its state and period moved by 1e-3, so that each setting does its own
// Newton iterations.
PeriodicOrbit orbit_guess(const MetronomeModel& model, const CaseFile& file, const StartSpec& start,
                          const InvariantSubspace& subspace);

// Newton from `guess` (its state, period and parameter values) at setting `s`, timed whole.
Result solve_orbit(const MetronomeModel& model, const PeriodicOrbit& guess,
                   const InvariantSubspace& subspace, const Setting& s);

// bench.csv's columns; `seconds_per_period` and `steps_per_period` are section (l)'s (one period
// with the monodromy at the solved orbit), empty elsewhere.
std::vector<std::string> bench_csv_columns();

// The bench.csv row of one solved orbit (sections (a)-(c) and (l)); NAN errors are written "-".
std::vector<std::string> orbit_csv_row(const std::string& problem, const Setting& s,
                                       const Result& r, double period_error, double mu_error,
                                       double k_error, double seconds_per_period = NAN,
                                       double steps_per_period = NAN);

// Median wall time of `repeats` runs of `work`.
template <class F>
double median_seconds(int repeats, F&& work) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const Stopwatch clock;
    work();
    t.push_back(clock.seconds());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// Median CPU time of the process over `repeats` runs of `work` (one thread): on a machine shared
// with other work the wall time of a run grows while this does not.
template <class F>
double median_cpu_seconds(int repeats, F&& work) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const std::clock_t begin = std::clock();
    work();
    t.push_back(static_cast<double>(std::clock() - begin) / CLOCKS_PER_SEC);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace sympathy::bench
