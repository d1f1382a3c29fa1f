#include "sympathy/continuation/basin_walk.hpp"

#include <algorithm>
#include <map>
#include <random>
#include <stdexcept>

namespace sympathy {

OptionCheck BasinWalkOptions::validate(int dimension, int parameters) const {
  if (parameter < 0 || parameter >= parameters)
    return OptionProblem{"parameter", "one of the system's parameters"};
  if (values.empty()) return OptionProblem{"values", "at least one value"};
  for (double v : values)
    if (!std::isfinite(v)) return OptionProblem{"values", "finite numbers"};
  if (starts < 1 || starts > 1000000)
    return OptionProblem{"starts", "an integer from 1 to 1000000"};
  if (lower.size() != dimension || upper.size() != dimension)
    return OptionProblem{
        "lower", "a bound for each of the " + std::to_string(dimension) + " states, and upper too"};
  for (int i = 0; i < dimension; ++i)
    if (!(std::isfinite(lower[i]) && std::isfinite(upper[i]) && lower[i] <= upper[i]))
      return OptionProblem{"upper", "finite bounds with lower <= upper for every state"};
  if (auto wrong = nested("run.", run.validate())) return wrong;
  return nested("tasks.", tasks.validate());
}

Eigen::VectorXd walk_start(const BasinWalkOptions& options, std::size_t j, std::size_t s) {
  std::mt19937_64 draw(task_seed(options.seed, j * static_cast<std::size_t>(options.starts) + s));
  Eigen::VectorXd z(options.lower.size());
  for (Eigen::Index i = 0; i < z.size(); ++i)
    z[i] = options.lower[i] + (options.upper[i] - options.lower[i]) * unit_uniform(draw());
  return z;
}

namespace {

// The name a run's fate counts under.
std::string share_name(const BasinWalkValue& v, const AttractorFate& f) {
  if (f.attractor >= 0) return v.attractors[f.attractor].name;
  return to_string(f.fate == Fate::NewOrbit ? Fate::Unresolved : f.fate);
}

// The highest k of the "new k" names among `attractors`.
int highest_new(const std::vector<Attractor>& attractors) {
  int k = 0;
  for (const auto& a : attractors)
    if (a.name.rfind("new ", 0) == 0) k = std::max(k, std::atoi(a.name.c_str() + 4));
  return k;
}

}  // namespace

BasinWalk walk_basins(const OdeSystem& system, const ParameterValues& p,
                      const std::vector<NamedBranch>& branches, const BasinWalkOptions& options,
                      const std::atomic<bool>* stop,
                      const std::vector<NamedEquilibria>& equilibria) {
  if (auto wrong = options.validate(system.dimension(), system.parameter_count()))
    throw std::invalid_argument(wrong->message());
  for (const auto& b : branches)
    if (!b.branch || b.branch->parameter != options.parameter)
      throw std::invalid_argument("walk_basins: branch '" + b.name +
                                  "' is not continued in the walked parameter");
  for (const auto& e : equilibria)
    if (!e.branch || e.branch->parameter != options.parameter)
      throw std::invalid_argument("walk_basins: equilibria '" + e.name +
                                  "' are not continued in the walked parameter");
  BasinWalk walk;
  int new_count = 0;
  for (std::size_t j = 0; j < options.values.size(); ++j) {
    if (stop && stop->load()) break;
    BasinWalkValue value;
    value.value = options.values[j];
    const ParameterValues at = system.with_parameter(p, options.parameter, value.value);
    const AttractorOptions& ao = options.run.attractors;
    std::vector<Attractor> named = attractors_on_branches(system, at, branches, ao);
    for (auto& a : attractors_at_rest_on_branches(system, at, equilibria, ao))
      if (std::none_of(named.begin(), named.end(),
                       [&](const Attractor& b) { return b.at_rest() && same_rest(b, a.rest); }))
        named.push_back(std::move(a));
    value.attractors = merge_attractors(
        system, std::move(named),
        walk.values.empty() ? std::vector<Attractor>{}
                            : continue_attractors(system, at, walk.values.back().attractors, ao),
        ao);
    if (options.on_value) options.on_value(j);
    const auto starts = static_cast<std::size_t>(options.starts);
    std::vector<std::optional<AttractorFate>> fates(starts);
    // A new orbit read back (a journal's row, another process's fate): solved again from its
    // state and period, where Newton stops at once (the same bits as the run's).
    const auto restore = [&](AttractorFate& f) {
      if (f.fate == Fate::NewOrbit && f.orbit && f.orbit->floquet.multipliers.empty())
        f.orbit = solve_periodic_orbit(system, at, f.orbit->state0, f.orbit->period,
                                       InvariantSubspace{}, options.run.attractors.orbit);
    };
    std::vector<bool> done(starts, false);
    if (options.journaled)
      for (std::size_t s = 0; s < starts; ++s) {
        fates[s] = options.journaled(j * starts + s);
        done[s] = fates[s].has_value();
        if (done[s]) restore(*fates[s]);
      }
    const std::function<std::optional<AttractorFate>(std::size_t)> work = [&](std::size_t s) {
      return run_to_attractor(system, at, walk_start(options, j, s), value.attractors, options.run,
                              stop);
    };
    const std::function<void(std::size_t, AttractorFate &&)> record = [&](std::size_t s,
                                                                          AttractorFate&& f) {
      restore(f);
      if (options.on_run) options.on_run(j * starts + s, f);
      fates[s] = std::move(f);
    };
    const TaskRunSummary summary =
        options.runner ? options.runner(starts, done, work, record)
                       : run_tasks<AttractorFate>(starts, done, work, record, options.tasks, stop);
    if (summary.interrupted) {
      walk.interrupted = true;
      break;
    }
    for (auto& f : fates) value.runs.push_back(std::move(*f));
    new_count = std::max(new_count, highest_new(value.attractors));
    std::vector<Attractor> found =
        name_new_attractors(system, value.runs, ao, static_cast<int>(value.attractors.size()),
                            new_count + 1, options.symmetries);
    new_count += static_cast<int>(found.size());
    for (auto& a : found) value.attractors.push_back(std::move(a));
    walk.values.push_back(std::move(value));
  }
  // Every name of the walk: the attractors in the order they first appear, then the other fates.
  std::vector<std::pair<std::string, std::string>> names;  // name, branch
  const auto add = [&](const std::string& n, const std::string& branch) {
    if (std::none_of(names.begin(), names.end(), [&](const auto& e) { return e.first == n; }))
      names.emplace_back(n, branch);
  };
  for (const auto& v : walk.values)
    for (const auto& a : v.attractors) add(a.name, a.branch);
  for (const Fate f : {Fate::Equilibrium, Fate::Torus, Fate::Unresolved, Fate::Failed})
    for (const auto& v : walk.values)
      for (const auto& r : v.runs)
        if (r.attractor < 0 && (r.fate == f || (f == Fate::Unresolved && r.fate == Fate::NewOrbit)))
          add(to_string(f), "");
  for (auto& v : walk.values) {
    std::map<std::string, std::size_t> counts;
    std::map<std::string, std::vector<double>> certified;  // the stop times of certified runs
    for (const auto& f : v.runs) {
      ++counts[share_name(v, f)];
      if (f.fate == Fate::Certified) certified[share_name(v, f)].push_back(f.stopped_at);
    }
    for (const auto& [n, branch] : names)
      v.shares.push_back(
          {n, branch, wilson_interval(counts[n], v.runs.size()), quartiles(certified[n])});
  }
  return walk;
}

std::vector<ShareChange> share_changes(const BasinWalk& walk,
                                       const std::vector<NamedBranch>& branches,
                                       const std::vector<NamedEquilibria>& equilibria) {
  std::vector<ShareChange> changes;
  for (std::size_t j = 0; j + 1 < walk.values.size(); ++j) {
    const BasinWalkValue &a = walk.values[j], &b = walk.values[j + 1];
    for (std::size_t k = 0; k < a.shares.size() && k < b.shares.size(); ++k) {
      const bool was = a.shares[k].proportion.count > 0, is = b.shares[k].proportion.count > 0;
      // Runs that ended nowhere (unresolved, failed) are no attractor that appears.
      const std::string& n = a.shares[k].name;
      if (was == is || n == to_string(Fate::Unresolved) || n == to_string(Fate::Failed)) continue;
      ShareChange c;
      c.name = a.shares[k].name;
      c.appears = is;
      c.before = a.value;
      c.after = b.value;
      const auto present = [&](const BasinWalkValue& v) {
        return std::any_of(v.attractors.begin(), v.attractors.end(),
                           [&](const Attractor& x) { return x.name == c.name; });
      };
      c.present_before = present(a);
      c.present_after = present(b);
      const double lo = std::min(a.value, b.value), hi = std::max(a.value, b.value);
      const auto add = [&](ShareChange::Event e) {
        const bool again = std::any_of(c.events.begin(), c.events.end(), [&](const auto& d) {
          return d.type == e.type &&
                 std::abs(d.parameter - e.parameter) <= 1e-9 * std::max(1.0, std::abs(e.parameter));
        });
        if (e.parameter > lo && e.parameter < hi && !again) c.events.push_back(std::move(e));
      };
      for (const auto& named : branches)
        for (const auto& e : named.branch->events)
          add({named.name, to_string(e.type), e.parameter, e.uncertainty, e.trusted()});
      for (const auto& named : equilibria)
        for (const auto& e : named.branch->events)
          if (e.type != EquilibriumEventType::UserPoint)
            add({named.name, to_string(e.type), e.parameter, e.uncertainty, e.located});
      changes.push_back(std::move(c));
    }
  }
  return changes;
}

}  // namespace sympathy
