// Basin shares continued along a parameter (issue 39, item 3): the values of one parameter walked
// in order; at each, the attractors are the stable orbits and equilibria the given branches hold
// there (attractors_on_branches, attractors_at_rest_on_branches) and those of the previous value
// continued to it by Newton (continue_attractors: an attractor keeps its name because it is the
// same orbit continued, merge_attractors), then random starts run to their fates (run_to_attractor)
// in parallel, and the stable orbits they found that are none of these are named "new k"
// (name_new_attractors) and carried on like the others. The share of each attractor at each value,
// with its 95% Wilson interval, is a curve along the parameter: where an attractor appears or
// disappears lies between two values, and a bifurcation the branches located there is where it
// happens.
//
// Deterministic: the starts of a value run in parallel, the values one after another, value j
// knowing only value j-1's finished results (never whatever finished first); start s of value j
// draws each state uniformly in the box from a generator seeded by task_seed(seed, j * starts +
// s). The results are the same bits for any number of threads.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/attractor_run.hpp"
#include "sympathy/continuation/task_runner.hpp"
#include "sympathy/core/proportion.hpp"
#include "sympathy/core/quartiles.hpp"

namespace sympathy {

struct BasinWalkOptions {
  int parameter = -1;            // the walked parameter's index among the system's
  std::vector<double> values;    // in the order walked
  int starts = 100;              // random starts per value
  Eigen::VectorXd lower, upper;  // the box the starts are drawn in, uniformly per state
  std::uint64_t seed = 1;
  AttractorRunOptions run;
  TaskRunOptions tasks;
  // The invariant subspaces the system declares (a case's starts'), to name a new attractor by
  // the symmetry it keeps (name_new_attractors).
  std::vector<InvariantSubspace> symmetries;
  // Told the index of each value as its runs start (progress; called on the walk's thread).
  std::function<void(std::size_t)> on_value;
  // A journal (basin_walk_journal.hpp), both optional; runs are numbered j * starts + s. Each
  // run's fate as it finishes (one call at a time, in the order they finish); and the fates an
  // earlier walk of the same study recorded, which are taken instead of running again (a new
  // orbit's solved again from its recorded state and period: the same bits).
  std::function<void(std::size_t, const AttractorFate&)> on_run;
  std::function<std::optional<AttractorFate>(std::size_t)> journaled;
  // How a value's runs are spread (optional; by default this machine's threads, run_tasks with
  // `tasks`): `run(count, done, work, record)` runs work(s) for every s < count with !done[s] and
  // hands each fate to record(s, fate), every fate on every process that walks (the command
  // line's MPI ranks: the manager's fates, sent to the workers as journal rows). A new orbit's
  // fate may come with its orbit's state0 and period alone: it is solved again, as a journaled one.
  using ValueRunner =
      std::function<TaskRunSummary(std::size_t, const std::vector<bool>&,
                                   const std::function<std::optional<AttractorFate>(std::size_t)>&,
                                   const std::function<void(std::size_t, AttractorFate&&)>&)>;
  ValueRunner runner;

  // The first field out of its domain, for a system of `dimension` states and `parameters`
  // named parameters.
  OptionCheck validate(int dimension, int parameters) const;
};

// The share of one attractor (or class of fates) at one value.
struct BasinWalkShare {
  std::string name;    // an attractor's, or "equilibrium", "unresolved", "failed"
  std::string branch;  // the branch its orbit lies on (empty: none, or not an orbit)
  Proportion proportion;
  // When the runs certified on it were (their stop times): how long its basin takes to
  // converge, from the user's distribution of starts (NaN where none was certified).
  Quartiles certified_at;
};

struct BasinWalkValue {
  double value = 0.0;
  // The attractors at it: those the branches hold and those continued from the previous value
  // (merge_attractors), then the new ones its runs found.
  std::vector<Attractor> attractors;
  std::vector<AttractorFate> runs;  // in start order; Certified, Reached, NewOrbit: `attractor`
                                    // indexes `attractors`
  // Every name of the walk: the attractors in the order they first appear in the values' lists
  // (the branches' first), then the other fates where a run has them ("equilibrium",
  // "unresolved", "failed").
  std::vector<BasinWalkShare> shares;
};

struct BasinWalk {
  std::vector<BasinWalkValue> values;  // those walked (fewer where interrupted)
  bool interrupted = false;
};

// Where an attractor's share (or the tori's or equilibria's) becomes nonzero (appears) or zero
// (disappears) between two neighbouring values of a walk, and the located events of the branches
// between them: where it happens (a branch point, fold or period doubling the branches found).
struct ShareChange {
  std::string name;
  bool appears = true;
  double before = 0.0, after = 0.0;  // the neighbouring values, in the walk's order
  // Whether the attractor is among the values' attractors: a share that falls to zero while its
  // orbit is still there (present at both) is the starts' sampling, not the attractor's end.
  bool present_before = false, present_after = false;
  struct Event {
    std::string branch;  // the branch of orbits or of equilibria that located it
    std::string type;    // "BP", "NS", "HB", ...
    double parameter = 0.0, uncertainty = 0.0;
    bool trusted = false;  // an orbit branch's trusted event, an equilibrium branch's located one
  };
  // Located on `branches` and `equilibria` with the parameter between the two, each once (the
  // mirror halves of a symmetric branch locate the same events: one type at one value to 1e-9
  // relative).
  std::vector<Event> events;
};
std::vector<ShareChange> share_changes(const BasinWalk& walk,
                                       const std::vector<NamedBranch>& branches,
                                       const std::vector<NamedEquilibria>& equilibria = {});

// The start of run `s` at value `j`: uniform in the box, from task_seed(seed, j * starts + s).
Eigen::VectorXd walk_start(const BasinWalkOptions& options, std::size_t j, std::size_t s);

// Walks options.values at parameter values `p` (the walked one set at each), with the attractors
// of `branches` and the stable equilibria of `equilibria` (each continued in
// options.parameter). Throws std::invalid_argument for invalid options (validate first to name
// the field) or a branch continued in another parameter.
BasinWalk walk_basins(const OdeSystem& system, const ParameterValues& p,
                      const std::vector<NamedBranch>& branches, const BasinWalkOptions& options,
                      const std::atomic<bool>* stop = nullptr,
                      const std::vector<NamedEquilibria>& equilibria = {});

}  // namespace sympathy
