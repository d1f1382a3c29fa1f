#include "sympathy/cases/basin_study.hpp"

#include <algorithm>
#include <map>
#include <random>
#include <stdexcept>

#include "sympathy/continuation/convergence_certificate.hpp"
#include "sympathy/continuation/task_runner.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

std::vector<double> GridAxis::values() const {
  std::vector<double> v;
  for (int i = 0; i < count; ++i)
    v.push_back(count == 1 ? from : i == count - 1 ? to : from + (to - from) * i / (count - 1));
  return v;
}

FlowOptions BasinOptions::default_flow() {
  FlowOptions o;
  o.rtol = 1e-8;
  o.atol = 1e-10;
  return o;
}

FlowOptions BasinOptions::classification_flow() {
  FlowOptions o;
  o.method = Method::ERK;
  o.sensitivities = Sensitivities::Augmented;  // an explicit method has no sensitivity module
  o.rtol = 1e-6;
  o.atol = 1e-8;
  return o;
}

OptionCheck BasinOptions::validate() const {
  if (grid.empty() || grid.size() > 2) return OptionProblem{"grid", "one or two parameters"};
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const std::string at = "grid[" + std::to_string(i) + "].";
    const GridAxis& a = grid[i];
    if (a.parameter.empty()) return OptionProblem{at + "parameter", "a parameter's name"};
    if (!std::isfinite(a.from)) return OptionProblem{at + "from", "a finite number"};
    if (!std::isfinite(a.to)) return OptionProblem{at + "to", "a finite number"};
    if (a.count < 1) return OptionProblem{at + "count", "at least one value"};
    if (a.count == 1 && a.to != a.from)
      return OptionProblem{at + "count", "at least two values from " + format_number(a.from) +
                                             " to " + format_number(a.to)};
    if (i == 1 && a.parameter == grid[0].parameter)
      return OptionProblem{at + "parameter", "a parameter other than the first's"};
  }
  if (starts < 1) return OptionProblem{"starts", "at least one start per grid point"};
  if (!std::isfinite(angle_min)) return OptionProblem{"angle_min", "a finite angle (rad)"};
  if (!(std::isfinite(angle_max) && angle_max > angle_min))
    return OptionProblem{"angle_max", "an angle above angle_min (rad)"};
  if (!(std::abs(angle_min) < 3.14159 && std::abs(angle_max) < 3.14159))
    return OptionProblem{std::abs(angle_min) < 3.14159 ? "angle_max" : "angle_min",
                         "an angle within (-pi, pi) rad"};
  if (!positive(dt)) return OptionProblem{"dt", "a positive number of seconds"};
  if (!(positive(t_end) && t_end > classifier.window + dt))
    return OptionProblem{"t_end", "a time longer than the classifier's window (" +
                                      format_number(classifier.window) + " s)"};
  if (dt > 0.05) return OptionProblem{"dt", "at most 0.05 s (a tenth of a period)"};
  if (t_end / dt > kMaxSamples)
    return OptionProblem{
        "dt", "at most 1e7 samples a run (t_end / dt = " + format_number(t_end / dt) + ")"};
  if (auto p = nested("classifier.", classifier.validate())) return p;
  if (confirm || early_stop)
    if (auto p = nested("orbit.", orbit.validate())) return p;
  if (early_stop) {
    if (candidate_starts.empty())
      return OptionProblem{"candidate_starts", "one or more starts to reach candidate orbits from"};
    if (auto p = nested("certificate.", certificate.validate())) return p;
  }
  return nested("flow.", flow.validate());
}

BasinStudy::BasinStudy(ModelSpec spec, Eigen::VectorXd initial, BasinOptions options)
    : spec_(std::move(spec)), initial_(std::move(initial)), options_(std::move(options)) {
  if (const auto problem = options_.validate())
    throw std::invalid_argument("BasinOptions: " + problem->message());
  points_ = 1;
  for (const auto& a : options_.grid) {
    if (!spec_.has_parameter(a.parameter))
      throw InputError("grid parameter '" + a.parameter +
                       "' is not one of the model's: " + join(spec_.parameter_names()));
    axes_.push_back(a.values());
    for (double v : axes_.back()) {
      ModelSpec at = spec_;
      at.set(a.parameter, v);
      const auto problems = at.problems();
      if (!problems.empty())
        throw InputError(a.parameter + " = " + format_double(v) + " is outside the model's " +
                         "domain: " + problems.front().first + " must be " +
                         problems.front().second);
    }
    points_ *= axes_.back().size();
  }
  const MetronomeModel model(spec_);
  if (initial_.size() != model.dimension())
    throw std::invalid_argument("BasinStudy: the initial state has the wrong size");
  for (int i = 0; i < model.metronome_count(); ++i) angle_index_.push_back(model.angle_index(i));
  groups_ = swing_groups(spec_);
  if (options_.classifier.stopped_amplitude.empty())
    for (const auto& m : spec_.metronomes)
      options_.classifier.stopped_amplitude.push_back(m.values.at("ths"));
}

std::vector<double> BasinStudy::values(std::size_t point) const {
  std::vector<double> v(axes_.size());
  for (std::size_t a = axes_.size(); a-- > 0;) {
    v[a] = axes_[a][point % axes_[a].size()];
    point /= axes_[a].size();
  }
  return v;
}

BasinTask BasinStudy::task(std::size_t index) const {
  if (index >= tasks()) throw std::out_of_range("BasinStudy::task: index beyond the tasks");
  BasinTask t;
  t.index = index;
  t.point = index / options_.starts;
  t.start = index % options_.starts;
  t.values = values(t.point);
  std::mt19937_64 generator(task_seed(options_.seed, index));
  for (int i = 0; i < pendula(); ++i)
    t.angles.push_back(options_.angle_min +
                       (options_.angle_max - options_.angle_min) * unit_uniform(generator()));
  return t;
}

bool is_locked(SyncState state) {
  switch (state) {
    case SyncState::InPhase:
    case SyncState::AntiPhase:
    case SyncState::InIn:
    case SyncState::AntiAnti:
    case SyncState::InAnti:
    case SyncState::Locked:
      return true;
    default:
      return false;
  }
}

ModelSpec BasinStudy::spec_at(const std::vector<double>& values) const {
  ModelSpec spec = spec_;
  for (std::size_t a = 0; a < options_.grid.size(); ++a)
    spec.set(options_.grid[a].parameter, values[a]);
  return spec;
}

std::shared_ptr<const std::vector<BasinCandidate>> BasinStudy::candidates(std::size_t point) const {
  std::lock_guard<std::mutex> guard(candidates_lock_);
  auto& found = candidates_[point];
  if (!found) {
    const MetronomeModel model(spec_at(values(point)));
    found = std::make_shared<const std::vector<BasinCandidate>>(
        basin_candidates(model, options_.candidate_starts, options_.orbit, options_.certificate,
                         groups_, options_.classifier, options_.dt));
  }
  return found;
}

std::optional<BasinRun> BasinStudy::run(const BasinTask& task,
                                        const std::atomic<bool>* stop) const {
  const MetronomeModel model(spec_at(task.values));
  Eigen::VectorXd z0 = initial_;
  for (int i = 0; i < pendula(); ++i) z0[angle_index_[i]] = task.angles[i];
  // A flow of its own per task: nothing carried from one task to the next, whatever thread.
  Flow flow(model, options_.flow);
  SyncClassifier classifier(groups_, options_.classifier);
  const std::vector<double> times = sample_times(options_.t_end, options_.dt);
  std::vector<double> angles(pendula());
  BasinRun run;
  // With early_stop, a certificate per candidate orbit at this point (each on this task's model).
  std::shared_ptr<const std::vector<BasinCandidate>> candidates;
  std::vector<ConvergenceCertificate> certificates;
  if (options_.early_stop) {
    candidates = this->candidates(task.point);
    for (const auto& c : *candidates) certificates.emplace_back(model, c.neighbourhood);
  }
  int certified = -1;
  double t_last = 0.0;
  bool stopped = false;
  try {
    stopped = flow.sample_until(
        z0, model.default_parameters(), 0.0, times, [&](double t, const Eigen::VectorXd& z) {
          for (int i = 0; i < pendula(); ++i) angles[i] = z[angle_index_[i]];
          classifier.add(t, angles);
          run.end_state = z;
          t_last = t;
          // Certified, and settled: no pendulum's phase can stray by half the phase tolerance
          // any more (an angle's scaled deviation at its zero crossing is one of its phase, to
          // first order), so no later crossing moves the time to synchronize.
          for (std::size_t c = 0; c < certificates.size(); ++c)
            if (certificates[c].add(t, z) &&
                certificates[c].bound(angle_index_) <= 0.25 * options_.classifier.phase_tolerance)
              certified = static_cast<int>(c);
          return (stop && stop->load()) || certified >= 0;
        });
  } catch (const IntegrationError&) {
    SyncResult& failed = run.sync;
    failed.state = SyncState::Failed;
    failed.name = to_string(SyncState::Failed);
    failed.phase_differences.assign(pendula() - 1, std::nan(""));
    failed.amplitudes.assign(pendula(), std::nan(""));
    return run;
  }
  if (stopped && certified < 0) return std::nullopt;
  if (options_.early_stop) run.stopped_at = t_last;
  if (certified >= 0) {
    // The run's future is the orbit, from its point at the certified return: one window of it
    // (or to t_end) for the classifier, at the run's own sampling times.
    const BasinCandidate& c = (*candidates)[certified];
    run.certified_by = c.start;
    const double t_return = certificates[certified].return_times().back();
    for (double t : times)
      if (t > t_last &&
          t <= std::min(options_.t_end, t_last + options_.classifier.window + options_.dt))
        classifier.add(t, c.angles_at(t - t_return));
  }
  run.sync = classifier.classify();
  if (options_.confirm && is_locked(run.sync.state)) {
    // Newton from the run's end with the period it measured; its failures are results.
    OrbitConfirmation c;
    try {
      const PeriodicOrbit orbit =
          solve_periodic_orbit(model, model.default_parameters(), run.end_state,
                               1.0 / run.sync.frequency, InvariantSubspace{}, options_.orbit);
      c.outcome = orbit.newton.outcome;
      c.converged = orbit.converged();
      if (c.converged) {
        c.period = orbit.period;
        c.stability = orbit.floquet.stability;
        c.max_modulus = orbit.floquet.max_modulus;
      }
    } catch (const IntegrationError&) {
      c.outcome = NewtonOutcome::GuessNotIntegrable;
    }
    run.orbit = c;
  }
  return run;
}

namespace {

// The rank of a class name in SyncState's order ("locked+..." ranks as Locked).
int state_rank(const std::string& name) {
  for (int s = 0; s <= static_cast<int>(SyncState::Failed); ++s) {
    const std::string n = to_string(static_cast<SyncState>(s));
    if (name == n || (static_cast<SyncState>(s) == SyncState::Locked && name.rfind(n, 0) == 0))
      return s;
  }
  return static_cast<int>(SyncState::Failed) + 1;
}

}  // namespace

std::vector<std::vector<BasinShare>> basin_shares(
    std::size_t points, const std::vector<std::pair<std::size_t, std::string>>& outcomes) {
  std::vector<std::string> states;
  std::vector<std::map<std::string, std::size_t>> counts(points);
  std::vector<std::size_t> runs(points, 0);
  for (const auto& [point, state] : outcomes) {
    if (point >= points) throw std::out_of_range("basin_shares: point beyond the grid");
    if (std::find(states.begin(), states.end(), state) == states.end()) states.push_back(state);
    ++counts[point][state];
    ++runs[point];
  }
  std::sort(states.begin(), states.end(), [](const std::string& a, const std::string& b) {
    const int ra = state_rank(a), rb = state_rank(b);
    return ra != rb ? ra < rb : a < b;
  });
  std::vector<std::vector<BasinShare>> shares(points);
  for (std::size_t p = 0; p < points; ++p)
    for (const auto& s : states) {
      const auto it = counts[p].find(s);
      shares[p].push_back({s, wilson_interval(it == counts[p].end() ? 0 : it->second, runs[p])});
    }
  return shares;
}

}  // namespace sympathy
