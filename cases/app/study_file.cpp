#include "cases/app/study_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <filesystem>
#include <set>

#include "cases/app/escapement_key.hpp"
#include "cases/app/saved_start_key.hpp"

namespace sympathy::app {

namespace {

// HBn, n a positive number: a Hopf point of equilibria (parse_hopf_name's form; checked here
// without the Hopf start's code, which the fuzz target does not build).
bool is_hopf_name(const std::string& text) {
  return text.size() > 2 && text.compare(0, 2, "HB") == 0 && text[2] != '0' &&
         text.find_first_not_of("0123456789", 2) == std::string::npos && text.size() <= 8;
}

}  // namespace

Study load_study(const std::string& path) {
  const toml::table root = read_toml(path, "study file");
  const TomlReader in(path);
  in.only(root, "",
          {"title", "case", "params", "escapement", "parameter", "axis", "accuracy", "branches",
           "equilibria", "equilibria_axis", "marks", "basins"});
  Study s;
  s.path = path;
  s.name = std::filesystem::path(path).stem().string();
  auto required = [&](const char* key) -> const toml::node& {
    const toml::node* n = root.get(key);
    if (!n) throw InputError(path + ": key '" + key + "' is missing");
    return *n;
  };
  s.title = root.get("title") ? in.string(*root.get("title"), "title") : s.name;
  const std::string case_file = in.string(required("case"), "case");
  s.case_path = (std::filesystem::path(path).parent_path() / case_file).lexically_normal().string();
  if (root.get("params")) s.params = in.string(*root.get("params"), "params");
  s.escapement = read_escapement_key(in, root);
  s.parameter = in.string(required("parameter"), "parameter");
  s.axis = root.get("axis") ? in.string(*root.get("axis"), "axis") : "phase";
  if (const toml::node* n = root.get("marks")) {
    if (!n->is_array()) in.fail(*n, "marks", "a list of the case's parameter sets");
    for (const auto& m : *n->as_array()) s.marks.push_back(in.string(m, "marks"));
  }
  if (s.axis != "phase" && s.axis != "frequency")
    in.fail(*root.get("axis"), "axis", "\"phase\" or \"frequency\"");
  // The integrator preset of every branch (apply_accuracy); `sympathy study --accuracy` overrides
  // it.
  Accuracy accuracy = Accuracy::Default;
  if (const toml::node* n = root.get("accuracy")) {
    const std::string text = in.string(*n, "accuracy");
    if (text != "fast" && text != "default" && text != "high")
      in.fail(*n, "accuracy", "\"fast\", \"default\" or \"high\"");
    accuracy = parse_accuracy(text, "accuracy");
  }
  s.accuracy = accuracy;
  if (const toml::node* n = root.get("equilibria_axis"))
    s.equilibria_axis = in.string(*n, "equilibria_axis");  // a state of the case: study_run
  // Branches of equilibria first: the periodic branches may start at their Hopf points.
  std::set<std::string> names;
  if (const toml::node* n = root.get("equilibria")) read_study_equilibria(in, *n, s, names);
  if (!root.get("branches") && s.equilibria.empty())
    throw InputError(path +
                     ": key 'branches' is missing; expected [[branches]] tables, [[equilibria]] "
                     "tables or both");
  if (root.get("equilibria_axis") && s.equilibria.empty())
    in.fail(*root.get("equilibria_axis"), "equilibria_axis",
            "only beside [[equilibria]] tables (the state their diagram is drawn in)");
  static const toml::array none;
  const toml::node& list = root.get("branches") ? *root.get("branches") : none;
  if (root.get("branches") && (!list.is_array_of_tables() || list.as_array()->empty()))
    in.fail(list, "branches", "one or more [[branches]] tables");
  int index = 0;
  for (const auto& entry : *list.as_array()) {
    ++index;
    const std::string prefix = "branches[" + std::to_string(index) + "].";
    const auto& t = *entry.as_table();
    in.only(t, prefix,
            {"name", "start", "from", "to", "at", "set", "initial", "max_points", "step",
             "max_step", "transient", "switch_at", "user_points", "start_data", "user_value",
             "stop_at", "parent", "from_point", "equilibria"});
    StudyBranch b;
    // The start may be left out: a branch switched at another's event takes the parent's, an
    // equation case file's branch its [states] (a metronome case file's needs one: study_run).
    for (const char* key : {"name", "from", "to"})
      if (!t.get(key))
        throw InputError(path + ":" + std::to_string(entry.source().begin.line) + ": key '" +
                         prefix + key + "' is missing");
    b.name = in.string(*t.get("name"), prefix + "name");
    if (!names.insert(b.name).second)
      in.fail(*t.get("name"), prefix + "name",
              "a name no other branch or equilibria entry has (it names files)");
    if (t.get("start")) b.request.start = in.string(*t.get("start"), prefix + "start");
    if (const toml::node* n = t.get("start_data")) {
      if (t.get("start"))
        in.fail(*n, prefix + "start_data", "either start or start_data, not both");
      b.start_data =
          (std::filesystem::path(path).parent_path() / in.string(*n, prefix + "start_data"))
              .lexically_normal()
              .string();
    }
    // A restart from a saved point: its own start and parameter values.
    b.saved = read_saved_start_keys(in, entry, prefix, "a branch or curve JSON",
                                    {"start", "start_data", "switch_at", "set", "initial"});
    b.request.parameter = s.parameter;
    b.request.from = in.number(*t.get("from"), prefix + "from");
    b.request.to = in.number(*t.get("to"), prefix + "to");
    if (auto* n = t.get("at")) b.request.at = in.number(*n, prefix + "at");
    if (auto* n = t.get("switch_at")) {
      std::string text = in.string(*n, prefix + "switch_at");
      const auto colon = text.find(':');
      const auto equilibria = colon == std::string::npos
                                  ? s.equilibria.end()
                                  : std::find_if(s.equilibria.begin(), s.equilibria.end(),
                                                 [&](const StudyEquilibria& e) {
                                                   return e.name == text.substr(0, colon);
                                                 });
      if (equilibria != s.equilibria.end()) {
        // NAME:HBn of an [[equilibria]] entry: the family born at its Hopf point, at its values.
        b.equilibria_parent = equilibria->name;
        text = text.substr(colon + 1);
        if (!is_hopf_name(text))
          in.fail(*n, prefix + "switch_at",
                  "a Hopf point of the equilibria '" + b.equilibria_parent + "' (" +
                      b.equilibria_parent +
                      ":HB1): only there are orbits born (the branches of equilibria born at "
                      "their BP: an [[equilibria]] entry with switch_at = \"" +
                      b.equilibria_parent + ":BP1\")");
        for (const char* own : {"set", "initial", "start_data", "equilibria"})
          if (t.get(own))
            in.fail(*t.get(own), prefix + own,
                    "no " + std::string(own) + " beside switch_at = \"" + b.equilibria_parent +
                        ":" + text + "\" (the family starts at that Hopf point, at its values)");
        if (b.request.start.empty()) b.request.start = equilibria->start;
      } else if (colon != std::string::npos) {
        b.parent = text.substr(0, colon);
        text = text.substr(colon + 1);
        const bool known = std::any_of(s.branches.begin(), s.branches.end(),
                                       [&](const StudyBranch& o) { return o.name == b.parent; });
        if (!known)
          in.fail(*n, prefix + "switch_at",
                  "an event of this branch (BP1) or of a branch listed before it (NAME:BP1); '" +
                      b.parent + "' is not one");
        const auto& parent =
            *std::find_if(s.branches.begin(), s.branches.end(),
                          [&](const StudyBranch& o) { return o.name == b.parent; });
        if (!parent.parent.empty() || !parent.request.switch_at.empty())
          in.fail(*n, prefix + "switch_at",
                  "a branch that is not itself switched ('" + b.parent + "' is)");
        if (b.request.start.empty() && b.start_data.empty()) {
          b.request.start = parent.request.start;
          b.start_data = parent.start_data;
        }
      }
      b.request.switch_at = text;
      // HBn: the family of orbits born at the n-th Hopf point of the equilibria through the
      // start over the window, or of the saved ones `equilibria` names.
      const bool hopf = is_hopf_name(text);
      if (hopf && !b.parent.empty())
        in.fail(*n, prefix + "switch_at",
                "a Hopf point of the equilibria (HB1, NAME:HB1 of an [[equilibria]] entry, or "
                "HB1 with equilibria = \"FILE.json\" for saved ones), not of another branch");
      if (!hopf)
        parse_event_name(b.request.switch_at, in.where(*n) + ": key '" + prefix + "switch_at'",
                         {BifurcationType::BranchPoint, BifurcationType::PeriodDoubling},
                         "a branch point or period doubling (BP1, PD1, or NAME:BP1), or a Hopf "
                         "point of the equilibria (HB1): only there is a branch born");
    }
    if (const toml::node* n = t.get("equilibria")) {
      // Saved equilibria (equilibria --json, relative to the study file) whose HBn switch_at
      // takes.
      if (b.request.switch_at.rfind("HB", 0) != 0)
        in.fail(*n, prefix + "equilibria", "only with switch_at = \"HB1\" (or HB2, ...)");
      b.request.parent_path =
          (std::filesystem::path(path).parent_path() / in.string(*n, prefix + "equilibria"))
              .lexically_normal()
              .string();
    }
    auto& o = b.request.continuation;
    apply_accuracy(accuracy, o);
    if (auto* n = t.get("transient")) {
      o.orbit.transient = in.number(*n, prefix + "transient");
      b.transient_given = true;
    }
    if (auto* n = t.get("max_points")) o.max_points = in.integer(*n, prefix + "max_points");
    if (auto* n = t.get("step")) o.initial_step = in.number(*n, prefix + "step");
    if (auto* n = t.get("max_step")) o.max_step = in.number(*n, prefix + "max_step");
    if (const toml::node* n = t.get("user_points")) {
      const std::string key = prefix + "user_points";
      if (!n->is_array()) in.fail(*n, key, "a list of values of the parameter, e.g. [20, 40]");
      for (const auto& v : *n->as_array()) {
        const double value = in.number(v, key);
        if (value < std::min(b.request.from, b.request.to) ||
            value > std::max(b.request.from, b.request.to))
          in.fail(
              v, key,
              "values between from and to (the branch never reaches " + format_number(value) + ")");
        o.user_points.push_back(value);
      }
    }
    // The engine's own validation, as the command line's (the same domains, named by key).
    const std::string where =
        path + ":" + std::to_string(entry.source().begin.line) + ": " + prefix;
    check_options(o.validate(), where);
    if (b.request.from == b.request.to)
      throw InputError(where + "from, " + prefix + "to: expected different values");
    if (b.request.at && !(*b.request.at > std::min(b.request.from, b.request.to) &&
                          *b.request.at < std::max(b.request.from, b.request.to)))
      throw InputError(where + "at: expected a value between from and to");
    for (const char* group : {"set", "initial", "user_value", "stop_at"}) {
      const toml::node* n = t.get(group);
      if (!n) continue;
      if (!n->is_table()) in.fail(*n, prefix + group, "a table of NAME = VALUE");
      const std::string g = group;
      auto& to = g == "set"          ? b.sets
                 : g == "initial"    ? b.request.initial
                 : g == "user_value" ? b.user_values
                                     : b.stops;
      for (auto&& [k, v] : *n->as_table())
        to.push_back({std::string(k.str()),
                      in.number(v, prefix + group + "." + std::string(k.str())), in.where(v)});
    }
    s.branches.push_back(std::move(b));
  }
  if (const toml::node* n = root.get("basins")) read_study_basins(in, *n, s);
  return s;
}

}  // namespace sympathy::app
