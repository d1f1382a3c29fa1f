// A basin study: how often each synchronized state wins from random starts, at each point of a
// grid of one or two platform parameters (the issue the paper leaves open: "the obtained results
// with AUTO only provide local stability information, and they do not provide information about
// the basin of attraction").
//
// The study is a list of tasks, grid point x start (task = point * starts + start, the second
// grid parameter varying fastest within the first), each one simulation from its own start: the
// pendula at angles drawn uniformly in [angle_min, angle_max] from a generator seeded by
// task_seed(seed, task) (continuation/task_runner.hpp), at rest, the platform at rest unless the
// case's initial values say otherwise; the end classified by SyncClassifier. Everything a task
// computes depends on its index alone, so the results do not depend on the threads or processes
// that ran them. Cost, measured on the row setup at Table II (8 random starts, 100 s each, one
// thread, on a 2-core machine shared with other builds): BDF at rtol 1e-8 (the default, as
// `simulate`) 0.37 s a run; Dormand-Prince (--method erk) at rtol 1e-6 0.20 s a run, with the same
// classes and the times to synchronize within 2e-5 s of BDF's.
#pragma once

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/cases/basin_candidates.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/sync_classifier.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/option_check.hpp"
#include "sympathy/core/proportion.hpp"

namespace sympathy {

// One parameter's values: count points evenly from `from` to `to` (count 1: `from` alone).
struct GridAxis {
  std::string parameter;
  double from = 0.0;
  double to = 0.0;
  int count = 1;

  std::vector<double> values() const;
};

struct BasinOptions {
  std::vector<GridAxis> grid;  // one or two parameters
  int starts = 100;            // random starts per grid point
  double angle_min = -0.6;     // rad, the pendula's start angles are uniform in [min, max]
  double angle_max = 0.6;      // rad
  std::uint64_t seed = 1;
  double t_end = 100.0;              // s, each simulation's length
  double dt = 0.01;                  // s, the classifier's sampling interval
  SyncClassifierOptions classifier;  // stopped_amplitude empty: each metronome's ths
  FlowOptions flow = default_flow();
  // Confirmation of a locked end state by Newton on the shooting problem, from the run's end and
  // the period it measured (solve_periodic_orbit, in the whole state space): the orbit it ends
  // near, and its stability. Off by default (it adds a monodromy per locked run).
  bool confirm = false;
  OrbitOptions orbit;
  // Stop a run once its fate is certain (convergence_certificate.hpp): once it is certified to
  // converge to one of the stable orbits reached at its grid point from `candidate_starts`
  // (basin_candidates.hpp, with `orbit`'s options). The classifier is then given that orbit's
  // motion for one window in place of the rest of the run, so the run gets the class and time
  // to synchronize a full-length run would. Off by default.
  bool early_stop = false;
  std::vector<BasinCandidateStart> candidate_starts;
  CertificateOptions certificate;

  // Simulation's accuracy: BDF at rtol 1e-8, atol 1e-10, as `sympathy simulate`.
  static FlowOptions default_flow();
  // The accuracy a classification needs, the default with early_stop: Dormand-Prince (ERK) at
  // rtol 1e-6, atol 1e-8. Measured (bench section (k), 1600 runs of 300 s at eight cases): every
  // class the same as default_flow's, the times to synchronize within 5e-4 s, 2.3 to 6 times
  // as fast.
  static FlowOptions classification_flow();
  // The first field out of its domain (grid[0].count, starts, angle_max, t_end, ...).
  OptionCheck validate() const;
};

struct BasinTask {
  std::size_t index = 0;
  std::size_t point = 0;       // grid point
  std::size_t start = 0;       // start at that point
  std::vector<double> values;  // the grid parameters' values
  std::vector<double> angles;  // the pendula's start angles, rad
};

// What Newton found from a locked run's end (BasinOptions::confirm).
struct OrbitConfirmation {
  bool converged = false;
  double period = std::nan("");  // s, the orbit's
  Stability stability = Stability::Marginal;
  double max_modulus = std::nan("");  // the largest non-trivial multiplier's modulus
  NewtonOutcome outcome = NewtonOutcome::NotRun;
};

struct BasinRun {
  SyncResult sync;
  Eigen::VectorXd end_state;               // the state at t_end (or where it stopped early)
  std::optional<OrbitConfirmation> orbit;  // with BasinOptions::confirm, for a locked state
  // With BasinOptions::early_stop: where the run stopped (t_end if it was never certified) and
  // the candidate that certified it (its start's name; empty if none).
  double stopped_at = std::nan("");
  std::string certified_by;
};

// Whether a state is locked (a periodic orbit to confirm): in-phase ... locked.
bool is_locked(SyncState state);

class BasinStudy {
 public:
  // `spec`: the case with its parameter set applied; `initial`: the state every start begins
  // from before its angles are drawn (platform displacement and velocities). Throws
  // std::invalid_argument for invalid options (validate() first to name the field), InputError for
  // a grid parameter the model does not have or a grid value outside the model's domain.
  BasinStudy(ModelSpec spec, Eigen::VectorXd initial, BasinOptions options);

  std::size_t points() const { return points_; }
  std::size_t tasks() const { return points_ * static_cast<std::size_t>(options_.starts); }
  const BasinOptions& options() const { return options_; }
  const ModelSpec& spec() const { return spec_; }
  int pendula() const { return static_cast<int>(spec_.metronomes.size()); }
  // The grid parameters' values at a point.
  std::vector<double> values(std::size_t point) const;
  BasinTask task(std::size_t index) const;

  // Simulates and classifies one task (and with options().confirm, confirms a locked end by
  // Newton); no result when `stop` became true during it. An integration failure is the result
  // SyncState::Failed.
  std::optional<BasinRun> run(const BasinTask& task, const std::atomic<bool>* stop = nullptr) const;

  // With early_stop: the candidates at a grid point, computed once (by whichever run asks
  // first; the same whatever thread or process computes them).
  std::shared_ptr<const std::vector<BasinCandidate>> candidates(std::size_t point) const;

 private:
  ModelSpec spec_at(const std::vector<double>& values) const;

  ModelSpec spec_;
  Eigen::VectorXd initial_;
  BasinOptions options_;
  std::vector<std::vector<double>> axes_;  // each grid parameter's values
  std::size_t points_ = 0;
  std::vector<std::vector<int>> groups_;
  std::vector<int> angle_index_;
  mutable std::mutex candidates_lock_;
  mutable std::map<std::size_t, std::shared_ptr<const std::vector<BasinCandidate>>> candidates_;
};

// The share of each state at one grid point, with its 95% Wilson interval.
struct BasinShare {
  std::string state;  // a class name, as in SyncResult::name
  Proportion proportion;
};
// Per grid point, the shares of every state named in `outcomes` (point, class name) at any
// point (zero counts included, so that every point lists the same states), in state order
// (SyncState's), locked states by name.
std::vector<std::vector<BasinShare>> basin_shares(
    std::size_t points, const std::vector<std::pair<std::size_t, std::string>>& outcomes);

}  // namespace sympathy
