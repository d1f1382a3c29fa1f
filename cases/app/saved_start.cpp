#include "cases/app/saved_start.hpp"

#include <algorithm>
#include <cstdio>

#include "cases/app/branch_run.hpp"
#include "cases/app/event_name.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy::app {

std::optional<SavedStart> saved_start(const Arguments& args) {
  if (!args.has("--from-point")) return std::nullopt;
  SavedStart s{args.text("--parent", ""), *args.value("--from-point")};
  if (s.path.empty())
    throw InputError("--from-point " + s.what +
                     ": expected --parent FILE too (the branch JSON, continue --json, it is in)");
  for (const char* own :
       {"--start", "--initial", "--start-data", "--switch-at", "--set", "--params"})
    if (args.has(own))
      throw InputError(std::string(own) + ": not with --from-point " + s.what +
                       " (the saved orbit is the start, at its own parameter values)");
  return s;
}

namespace {

// An integer index ("12", "-3"), or nullopt.
std::optional<int> index_of(const std::string& text) {
  if (text.empty() || text.size() > 9) return std::nullopt;
  const std::size_t digits = text[0] == '-' ? 1 : 0;
  if (digits == text.size() || text.find_first_not_of("0123456789", digits) != std::string::npos)
    return std::nullopt;
  return std::stoi(text);
}

}  // namespace

SavedOrbit read_saved_orbit(const SavedStart& start, const OdeSystem& system) {
  const Branch branch = read_branch_json(start.path, system, InvariantSubspace());
  SavedOrbit saved;
  saved.path = start.path;
  double at = 0.0;    // the branch's parameter there
  std::string label;  // "point 12", "UZ1"
  if (const auto index = index_of(start.what)) {
    const auto p = std::find_if(branch.points.begin(), branch.points.end(),
                                [&](const ContinuationPoint& q) { return q.index == *index; });
    if (p == branch.points.end()) {
      const auto [lo, hi] =
          std::minmax_element(branch.points.begin(), branch.points.end(),
                              [](const auto& a, const auto& b) { return a.index < b.index; });
      throw InputError(
          "--from-point " + start.what + ": " + start.path + " has no point " + start.what +
          (branch.points.empty() ? std::string("; it has none")
                                 : "; expected an index from " + std::to_string(lo->index) +
                                       " to " + std::to_string(hi->index)));
    }
    saved.state0 = p->orbit.state0;
    saved.period = p->orbit.period;
    saved.segments = std::max(1, p->orbit.segments);
    at = p->parameter;
    label = "point " + start.what;
  } else {
    const EventName event = parse_event_name(
        start.what, "--from-point",
        {BifurcationType::Fold, BifurcationType::BranchPoint, BifurcationType::PeriodDoubling,
         BifurcationType::NeimarkSacker, BifurcationType::UserPoint},
        "a point's index along the branch (its JSON's points[].index), or an event: LP, BP, PD, "
        "NS or UZ followed by its number along the branch (e.g. UZ1)");
    const Bifurcation& e = find_event(branch, event, "--from-point");
    saved.state0 = e.state0;
    saved.period = e.period;
    const int n = system.dimension();
    const long states = e.unknowns.size() - (system.autonomous() ? 1 : 0);
    saved.segments = n > 0 && states >= n && states % n == 0 ? static_cast<int>(states / n) : 1;
    at = e.parameter;
    label = start.what;
  }
  saved.values = system.with_parameter(branch.start_values, branch.parameter, at);
  char value[96];
  std::snprintf(value, sizeof value, " (%s = %.10g)", branch.parameter_name.c_str(), at);
  saved.description = start.path + ", " + label + value;
  if (!(saved.period > 0.0))
    throw InputError("--from-point " + start.what + ": " + start.path +
                     " gives it no positive period; expected a branch JSON written by continue "
                     "--json");
  return saved;
}

}  // namespace sympathy::app
