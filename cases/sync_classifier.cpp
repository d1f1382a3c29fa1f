#include "sympathy/cases/sync_classifier.hpp"

#include <algorithm>
#include <cstdio>
#include <numbers>
#include <stdexcept>

namespace sympathy {

namespace {

constexpr double kPi = std::numbers::pi;

// An angle in (-pi, pi].
double wrap(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

// The circular mean of angles, in (-pi, pi].
double circular_mean(const std::vector<double>& a) {
  double s = 0.0, c = 0.0;
  for (double v : a) {
    s += std::sin(v);
    c += std::cos(v);
  }
  return wrap(std::atan2(s, c));
}

// The crossing of `crossings` (sorted) nearest to t; NaN if there is none.
double nearest(const std::vector<double>& crossings, double t) {
  if (crossings.empty()) return std::nan("");
  const auto it = std::lower_bound(crossings.begin(), crossings.end(), t);
  if (it == crossings.end()) return crossings.back();
  if (it == crossings.begin()) return *it;
  return (t - *(it - 1) <= *it - t) ? *(it - 1) : *it;
}

}  // namespace

std::string to_string(SyncState state) {
  switch (state) {
    case SyncState::InPhase:
      return "in-phase";
    case SyncState::AntiPhase:
      return "anti-phase";
    case SyncState::InIn:
      return "in-in";
    case SyncState::AntiAnti:
      return "anti-anti";
    case SyncState::InAnti:
      return "in-anti";
    case SyncState::Locked:
      return "locked";
    case SyncState::NotSynchronized:
      return "not-synchronized";
    case SyncState::Stopped:
      return "stopped";
    case SyncState::Undetermined:
      return "undetermined";
    case SyncState::Failed:
      return "failed";
  }
  return "?";
}

OptionCheck SyncClassifierOptions::validate() const {
  if (!positive(window)) return OptionProblem{"window", "a positive number of seconds"};
  if (!(positive(phase_tolerance) && phase_tolerance < kPi / 2))
    return OptionProblem{"phase_tolerance", "a positive angle below pi/2 rad"};
  if (!(positive(lock_tolerance) && lock_tolerance < kPi / 2))
    return OptionProblem{"lock_tolerance", "a positive angle below pi/2 rad"};
  for (double a : stopped_amplitude)
    if (!non_negative(a)) return OptionProblem{"stopped_amplitude", "non-negative angles (rad)"};
  return std::nullopt;
}

SyncClassifier::SyncClassifier(std::vector<std::vector<int>> groups, SyncClassifierOptions options)
    : groups_(std::move(groups)), options_(std::move(options)) {
  if (const auto problem = options_.validate())
    throw std::invalid_argument("SyncClassifierOptions: " + problem->message());
  for (const auto& g : groups_) pendula_ += static_cast<int>(g.size());
  std::vector<bool> seen(pendula_, false);
  for (const auto& g : groups_) {
    if (g.empty()) throw std::invalid_argument("SyncClassifier: an empty group");
    for (int i : g) {
      if (i < 0 || i >= pendula_ || seen[i])
        throw std::invalid_argument("SyncClassifier: groups must hold each pendulum once");
      seen[i] = true;
    }
  }
  if (pendula_ == 0) throw std::invalid_argument("SyncClassifier: no pendulum");
  if (!options_.stopped_amplitude.empty() &&
      static_cast<int>(options_.stopped_amplitude.size()) != pendula_)
    throw std::invalid_argument("SyncClassifier: one stopped_amplitude per pendulum");
  crossings_.resize(pendula_);
}

void SyncClassifier::add(double t, std::span<const double> angles) {
  if (static_cast<int>(angles.size()) != pendula_)
    throw std::invalid_argument("SyncClassifier::add: one angle per pendulum");
  if (!started_) {
    started_ = true;
    t_first_ = t;
  } else {
    const auto& [t0, a0] = recent_.back();
    for (int i = 0; i < pendula_; ++i)
      if (a0[i] < 0.0 && angles[i] >= 0.0)
        crossings_[i].push_back(t0 + (t - t0) * (-a0[i]) / (angles[i] - a0[i]));
  }
  recent_.emplace_back(t, std::vector<double>(angles.begin(), angles.end()));
  while (recent_.size() > 2 && recent_.front().first < t - options_.window) recent_.pop_front();
}

SyncResult SyncClassifier::classify() const {
  SyncResult r;
  r.phase_differences.assign(pendula_ - 1, std::nan(""));
  r.amplitudes.assign(pendula_, std::nan(""));
  const auto done = [&r](SyncState s) {
    r.state = s;
    r.name = to_string(s);
    return r;
  };
  if (!started_) return done(SyncState::Undetermined);
  const double t_end = recent_.back().first;
  const double t_window = t_end - options_.window;
  if (t_window < t_first_) return done(SyncState::Undetermined);

  // Amplitudes over the window.
  std::vector<double> lo = recent_.front().second, hi = lo;
  for (const auto& [t, a] : recent_)
    for (int i = 0; i < pendula_; ++i) {
      lo[i] = std::min(lo[i], a[i]);
      hi[i] = std::max(hi[i], a[i]);
    }
  for (int i = 0; i < pendula_; ++i) r.amplitudes[i] = 0.5 * (hi[i] - lo[i]);
  for (std::size_t i = 0; i < options_.stopped_amplitude.size(); ++i)
    if (r.amplitudes[i] < options_.stopped_amplitude[i]) return done(SyncState::Stopped);

  // Pendulum 1's crossings in the window and its period.
  const auto& ref = crossings_[0];
  const auto in_window = [t_window](const std::vector<double>& c) {
    return static_cast<long>(c.end() - std::lower_bound(c.begin(), c.end(), t_window));
  };
  const long n_ref = in_window(ref);
  if (n_ref < 3) return done(SyncState::Undetermined);
  const std::size_t first = ref.size() - n_ref;
  r.frequency = (n_ref - 1) / (ref.back() - ref[first]);
  for (int i = 1; i < pendula_; ++i)
    if (std::abs(in_window(crossings_[i]) - n_ref) > 1) return done(SyncState::NotSynchronized);

  // Phase differences at each crossing of pendulum 1 (from its second on), and their means and
  // departures over the window.
  const std::size_t m = ref.size();
  std::vector<std::vector<double>> phase(pendula_, std::vector<double>(m, 0.0));
  for (std::size_t j = 1; j < m; ++j)
    for (int i = 1; i < pendula_; ++i)
      phase[i][j] =
          wrap(2.0 * kPi * (ref[j] - nearest(crossings_[i], ref[j])) / (ref[j] - ref[j - 1]));
  const std::size_t j0 = std::max<std::size_t>(first, 1);
  std::vector<double> mean(pendula_, 0.0);
  for (int i = 1; i < pendula_; ++i) {
    if (std::isnan(phase[i][m - 1])) return done(SyncState::NotSynchronized);
    mean[i] = circular_mean({phase[i].begin() + j0, phase[i].end()});
    for (std::size_t j = j0; j < m; ++j)
      if (std::abs(wrap(phase[i][j] - mean[i])) > options_.lock_tolerance)
        return done(SyncState::NotSynchronized);
    r.phase_differences[i - 1] = mean[i];
  }

  // Name the locked state by its groups; `targets` are the differences (pendulum, reference
  // pendulum, value) that define it.
  struct Target {
    int pendulum, reference;
    double value;
  };
  std::vector<Target> targets;
  std::vector<char> patterns;  // per group of two or more: 'i' in, 'a' anti
  bool named = true;
  for (const auto& g : groups_) {
    if (g.size() < 2) continue;
    const int lead = g[0];
    bool in = true, anti = g.size() == 2;
    for (std::size_t k = 1; k < g.size(); ++k) {
      const double d = wrap(mean[g[k]] - mean[lead]);
      in = in && std::abs(d) <= options_.phase_tolerance;
      anti = anti && std::abs(wrap(d - kPi)) <= options_.phase_tolerance;
    }
    if (!in && !anti) {
      named = false;
      break;
    }
    patterns.push_back(in ? 'i' : 'a');
    for (std::size_t k = 1; k < g.size(); ++k) targets.push_back({g[k], lead, in ? 0.0 : kPi});
  }
  if (named && patterns.size() == 1 && groups_.size() == 1) {
    r.state = patterns[0] == 'i' ? SyncState::InPhase : SyncState::AntiPhase;
  } else if (named && patterns.size() == 2 && groups_.size() == 2) {
    const int anti = (patterns[0] == 'a') + (patterns[1] == 'a');
    r.state = anti == 0 ? SyncState::InIn : anti == 2 ? SyncState::AntiAnti : SyncState::InAnti;
  } else {
    r.state = SyncState::Locked;
    targets.clear();
    for (int i = 1; i < pendula_; ++i) targets.push_back({i, 0, mean[i]});
  }
  r.name = to_string(r.state);
  // A locked state's name: its phase differences rounded to multiples of pi/16 (0.196 rad), so
  // that runs ending on one orbit share a name. (Rounded to 0.01 rad, the row setup's two orbits
  // born at the anti-phase BP split into "locked+2.94" and "locked+2.95" at k = 45 N/m.)
  if (r.state == SyncState::Locked)
    for (int i = 1; i < pendula_; ++i) {
      const double quantum = kPi / 16.0;
      const double named = wrap(std::round(mean[i] / quantum) * quantum);
      char text[32];
      std::snprintf(text, sizeof text, "%s%+.2f", i > 1 ? "/" : "", named);
      r.name += text;
    }

  // Time to synchronize: after the last crossing where a defining difference was out of bounds.
  std::size_t settled = 1;
  for (std::size_t j = 1; j < m; ++j)
    for (const auto& [i, k, value] : targets)
      if (std::abs(wrap(phase[i][j] - phase[k][j] - value)) > options_.phase_tolerance)
        settled = j + 1;
  r.time_to_sync = settled < m ? ref[settled] : t_end;
  return r;
}

std::vector<std::vector<int>> swing_groups(const ModelSpec& spec) {
  std::vector<std::vector<int>> groups;
  std::vector<double> angles;
  for (std::size_t i = 0; i < spec.metronomes.size(); ++i) {
    const double a = spec.metronomes[i].values.at("angle");
    const auto it = std::find(angles.begin(), angles.end(), a);
    if (it == angles.end()) {
      angles.push_back(a);
      groups.push_back({static_cast<int>(i)});
    } else {
      groups[it - angles.begin()].push_back(static_cast<int>(i));
    }
  }
  return groups;
}

}  // namespace sympathy
