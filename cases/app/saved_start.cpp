#include "cases/app/saved_start.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

#include "cases/app/branch_run.hpp"
#include "cases/app/event_name.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/json_reader.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy::app {

std::optional<SavedStart> saved_start(const Arguments& args) {
  if (!args.has("--from-point")) return std::nullopt;
  SavedStart s{args.text("--parent", ""), *args.value("--from-point")};
  if (s.path.empty())
    throw InputError("--from-point " + s.what +
                     ": expected --parent FILE too (the JSON it is saved in: continue, curve or "
                     "equilibria --json)");
  for (const char* own :
       {"--start", "--initial", "--start-data", "--switch-at", "--set", "--params"})
    if (args.has(own))
      throw InputError(std::string(own) + ": not with --from-point " + s.what +
                       " (the saved point is the start, at its own parameter values)");
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

// Whether `path` holds a two-parameter curve (curve --json: its two parameters' names as
// `first` and `second`), not a branch.
bool is_curve_json(const JsonReader& file) {
  const nlohmann::json& j = file.root();
  return j.is_object() && j.contains("first") && j["first"].is_string() && j.contains("second") &&
         j["second"].is_string();
}

// A point of a curve (curve --json) by its index: its orbit at both of its parameters' values
// (AUTO's restart from a label of a two-parameter run). Its events are located on the points'
// curve, not orbits of their own with a name to restart from: points only.
SavedOrbit read_curve_point(const JsonReader& file, const SavedStart& start,
                            const OdeSystem& system) {
  const auto index = index_of(start.what);
  if (!index)
    throw InputError("--from-point " + start.what + ": " + start.path +
                     " is a curve (curve --json); expected a point's index along it (its "
                     "points[].index)");
  return file.read([&](const nlohmann::json& j) {
    const std::string first = j["first"], second = j["second"];
    const auto names = system.parameter_names();
    for (const std::string& name : {first, second})
      if (std::find(names.begin(), names.end(), name) == names.end())
        throw InputError(start.path + ": the curve's parameter '" + name +
                         "' is not one of this case's");
    const nlohmann::json& points = file.key(j, "points", start.path);
    int lo = 0, hi = 0;
    for (const nlohmann::json& p : points) {
      const int i = p.at("index");
      lo = std::min(lo, i);
      hi = std::max(hi, i);
      if (i != *index) continue;
      SavedOrbit saved;
      saved.path = start.path;
      saved.state0 =
          file.numbers(file.key(p, "state0", "points"), "points[].state0", system.dimension());
      saved.period = p.at("period");
      saved.segments = 1;  // a curve's orbits are single-shooting ones
      ParameterValues values = file.numbers(file.key(j, "parameter_values", start.path),
                                            "parameter_values", system.parameter_values_size());
      const double a = p.at("first"), b = p.at("second");
      values = system.with_parameter(values, system.parameter_index(first), a);
      saved.values = system.with_parameter(values, system.parameter_index(second), b);
      char where[160];
      std::snprintf(where, sizeof where, ", point %d (%s = %.10g, %s = %.10g)", *index,
                    first.c_str(), a, second.c_str(), b);
      saved.description = start.path + where;
      if (!(saved.period > 0.0))
        throw InputError("--from-point " + start.what + ": " + start.path +
                         " gives it no positive period; expected a curve JSON written by "
                         "curve --json");
      return saved;
    }
    throw InputError("--from-point " + start.what + ": " + start.path + " has no point " +
                     start.what + "; expected an index from " + std::to_string(lo) + " to " +
                     std::to_string(hi));
  });
}

}  // namespace

SavedOrbit read_saved_orbit(const SavedStart& start, const OdeSystem& system) {
  {
    const JsonReader file(start.path,
                          "a branch JSON (continue --json) or a curve JSON (curve --json)");
    if (is_curve_json(file)) return read_curve_point(file, start, system);
  }
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

SavedEquilibrium read_saved_equilibrium(const SavedStart& start, const OdeSystem& system) {
  const EquilibriumBranch branch = read_equilibria_json(start.path, system);
  SavedEquilibrium saved;
  double at = 0.0;
  std::string label;
  if (const auto index = index_of(start.what)) {
    const auto p = std::find_if(branch.points.begin(), branch.points.end(),
                                [&](const EquilibriumPoint& q) { return q.index == *index; });
    if (p == branch.points.end())
      throw InputError("--from-point " + start.what + ": " + start.path + " has no point " +
                       start.what + "; expected the index of one of its points (points[].index)");
    saved.state = p->state;
    at = p->parameter;
    label = "point " + start.what;
  } else {
    // TYPE and its number among that type's events along the branch: UZ2, HB1.
    const std::size_t digits = start.what.find_first_of("0123456789");
    const std::string type = start.what.substr(0, digits);
    const auto number =
        digits == std::string::npos ? std::nullopt : index_of(start.what.substr(digits));
    std::string list;
    std::map<std::string, int> seen;
    const EquilibriumEvent* found = nullptr;
    for (const auto& e : branch.events) {
      const std::string name = to_string(e.type) + std::to_string(++seen[to_string(e.type)]);
      list += (list.empty() ? "" : ", ") + name;
      if (number && to_string(e.type) == type && seen[type] == *number) found = &e;
    }
    if (!found)
      throw InputError("--from-point " + start.what + ": " + start.path +
                       " has no such point or event; expected a point's index or one of its "
                       "events: " +
                       (list.empty() ? std::string("it has none") : list));
    saved.state = found->state;
    at = found->parameter;
    label = start.what;
  }
  saved.values = system.with_parameter(branch.start_values, branch.parameter, at);
  char value[96];
  std::snprintf(value, sizeof value, " (%s = %.10g)", branch.parameter_name.c_str(), at);
  saved.description = start.path + ", " + label + value;
  return saved;
}

}  // namespace sympathy::app
