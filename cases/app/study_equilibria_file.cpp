// A study file's [[equilibria]] tables (load_study reads the rest): each one `equilibria` run in
// the study's parameter, every key checked here, before the case is loaded, with the file, the
// line and the key in each message; what needs the case (its starts, ranges, saved points) is
// checked by study_run before any work.
#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>

#include "cases/app/saved_start_key.hpp"
#include "cases/app/study_file.hpp"

namespace sympathy::app {

namespace {

StudyEquilibria read_entry(const TomlReader& in, const toml::node& entry, const std::string& prefix,
                           const Study& s) {
  const auto& t = *entry.as_table();
  in.only(t, prefix,
          {"name", "start", "from", "to", "at", "set", "initial", "max_points", "step", "max_step",
           "user_points", "parent", "from_point", "switch_at"});
  for (const char* key : {"name", "from", "to"})
    if (!t.get(key)) throw InputError(in.where(entry) + ": key '" + prefix + key + "' is missing");
  StudyEquilibria e;
  e.name = in.string(*t.get("name"), prefix + "name");
  if (e.name.empty() || e.name.find_first_of("/\\") != std::string::npos)
    in.fail(*t.get("name"), prefix + "name", "a name without slashes (it names files)");
  if (const toml::node* n = t.get("start")) e.start = in.string(*n, prefix + "start");
  e.from = in.number(*t.get("from"), prefix + "from");
  e.to = in.number(*t.get("to"), prefix + "to");
  if (e.from == e.to) in.fail(*t.get("to"), prefix + "to", "a value other than from");
  if (const toml::node* n = t.get("at")) {
    e.at = in.number(*n, prefix + "at");
    if (!(*e.at > std::min(e.from, e.to) && *e.at < std::max(e.from, e.to)))
      in.fail(*n, prefix + "at", "a value between from and to");
  }

  // A saved point or event of an earlier equilibria run (equilibria --parent F --from-point P):
  // its state and every parameter value are the start.
  e.saved = read_saved_start_keys(in, entry, prefix, "an equilibria JSON",
                                  {"start", "switch_at", "set", "initial"});

  if (const toml::node* n = t.get("switch_at")) {
    const std::string key = prefix + "switch_at";
    std::string text = in.string(*n, key);
    if (const auto colon = text.find(':'); colon != std::string::npos) {
      e.parent = text.substr(0, colon);
      text = text.substr(colon + 1);
      const bool known = std::any_of(s.equilibria.begin(), s.equilibria.end(),
                                     [&](const StudyEquilibria& o) { return o.name == e.parent; });
      if (!known)
        in.fail(*n, key,
                "a branch point of this entry's equilibria (BP1) or of an [[equilibria]] entry "
                "listed before it (NAME:BP1); '" +
                    e.parent + "' is not one");
      // The born branch starts at the parent's BP, at the parent's parameter values.
      for (const char* own : {"start", "set", "initial"})
        if (t.get(own))
          in.fail(*t.get(own), prefix + own,
                  "no " + std::string(own) + " beside switch_at = \"" + e.parent + ":" + text +
                      "\" (the branch starts at that branch point, at " + e.parent +
                      "'s parameter values)");
    }
    const EventName name = parse_event_name(
        text, in.where(*n) + ": key '" + key + "'", {BifurcationType::BranchPoint},
        "a branch point of the equilibria, BP followed by its number along them (BP1, or "
        "NAME:BP1): only there is a branch of equilibria born (the orbits born at a Hopf point: "
        "a [[branches]] entry with switch_at = \"NAME:HB1\")");
    e.switch_at = name.ordinal;
    if (e.at)
      in.fail(*t.get("at"), prefix + "at",
              "no at beside switch_at (the born branch runs "
              "both ways from its branch point)");
  }

  EquilibriumOptions& o = e.options;
  o.lower = std::min(e.from, e.to);
  o.upper = std::max(e.from, e.to);
  if (const toml::node* n = t.get("max_points"))
    o.max_points = in.integer(*n, prefix + "max_points");
  if (const toml::node* n = t.get("step")) o.initial_step = in.number(*n, prefix + "step");
  if (const toml::node* n = t.get("max_step")) o.max_step = in.number(*n, prefix + "max_step");
  if (const toml::node* n = t.get("user_points")) {
    const std::string key = prefix + "user_points";
    if (!n->is_array()) in.fail(*n, key, "a list of values of the parameter, e.g. [0.1, 0.2]");
    for (const auto& v : *n->as_array()) {
      const double value = in.number(v, key);
      if (value < o.lower || value > o.upper)
        in.fail(
            v, key,
            "values between from and to (the branch never reaches " + format_number(value) + ")");
      o.user_points.push_back(value);
    }
  }
  // The engine's own validation, as the command line's (the same domains, named by key).
  check_options(o.validate(), in.where(entry) + ": " + prefix);
  for (const char* group : {"set", "initial"}) {
    const toml::node* n = t.get(group);
    if (!n) continue;
    if (!n->is_table()) in.fail(*n, prefix + group, "a table of NAME = VALUE");
    auto& to = std::string(group) == "set" ? e.sets : e.initial;
    for (auto&& [k, v] : *n->as_table())
      to.push_back({std::string(k.str()), in.number(v, prefix + group + "." + std::string(k.str())),
                    in.where(v)});
  }
  return e;
}

}  // namespace

void read_study_equilibria(const TomlReader& in, const toml::node& list, Study& s,
                           std::set<std::string>& names) {
  if (!list.is_array_of_tables() || list.as_array()->empty())
    in.fail(list, "equilibria", "one or more [[equilibria]] tables");
  int index = 0;
  for (const auto& entry : *list.as_array()) {
    const std::string prefix = "equilibria[" + std::to_string(++index) + "].";
    StudyEquilibria e = read_entry(in, entry, prefix, s);
    if (!names.insert(e.name).second)
      in.fail(*entry.as_table()->get("name"), prefix + "name",
              "a name no other branch or equilibria entry has (it names files)");
    s.equilibria.push_back(std::move(e));
  }
}

}  // namespace sympathy::app
