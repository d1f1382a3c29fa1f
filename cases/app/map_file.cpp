#include "cases/app/map_file.hpp"

#include <toml++/toml.h>

#include <filesystem>
#include <set>

#include "cases/app/escapement_key.hpp"
#include "cases/app/saved_start_key.hpp"
#include "sympathy/cases/toml_reader.hpp"

namespace sympathy::app {

namespace {

MapAxis read_axis(const TomlReader& in, const toml::table& root, const std::string& key) {
  const toml::node* n = root.get(key);
  if (!n) throw InputError(in.path() + ": key '" + key + "' is missing");
  const toml::table& t = in.table(*n, key);
  in.only(t, key + ".", {"parameter", "from", "to", "points"});
  for (const char* k : {"parameter", "from", "to"})
    if (!t.get(k)) throw InputError(in.where(*n) + ": key '" + key + "." + k + "' is missing");
  MapAxis a;
  a.parameter = in.string(*t.get("parameter"), key + ".parameter");
  a.from = in.number(*t.get("from"), key + ".from");
  a.to = in.number(*t.get("to"), key + ".to");
  if (!(a.from < a.to)) in.fail(*t.get("to"), key + ".to", "a value above " + key + ".from");
  a.points = 25;
  if (const toml::node* p = t.get("points")) {
    a.points = in.integer(*p, key + ".points");
    if (a.points != 0 && (a.points < 2 || a.points > 400))
      in.fail(*p, key + ".points", "0 (no stability grid) or an integer from 2 to 400");
  }
  return a;
}

// An [[orbits]] or [[equilibria]] entry's keys, the same for both: its name (unique across both
// lists: it names files), start, at, or a saved point (parent and from_point).
template <class Entry>
void read_entry(const TomlReader& in, const MapStudy& s, const toml::node& entry,
                const std::string& prefix, std::set<std::string>& names, Entry& o) {
  const auto& t = *entry.as_table();
  if (!t.get("name")) throw InputError(in.where(entry) + ": key '" + prefix + "name' is missing");
  o.name = in.string(*t.get("name"), prefix + "name");
  // Required for a metronome case file (checked with the case); an equation case file's
  // default start is its [states].
  if (const toml::node* start = t.get("start")) o.start = in.string(*start, prefix + "start");
  // A saved run's point or event, as continue's --parent and --from-point; read with the case,
  // before any work.
  o.saved = read_saved_start_keys(in, entry, prefix, "a saved run's JSON", {"start"});
  if (o.name.empty() || o.name.find_first_of("/\\") != std::string::npos)
    in.fail(*t.get("name"), prefix + "name", "a name without slashes (it names files)");
  if (const toml::node* at = t.get("at")) {
    o.at = in.number(*at, prefix + "at");
    if (!(*o.at > s.first.from && *o.at < s.first.to))
      in.fail(*at, prefix + "at", "a value between first.from and first.to");
  }
  if (!names.insert(o.name).second)
    in.fail(*t.get("name"), prefix + "name", "a name no other orbit or equilibria entry has");
}

}  // namespace

MapStudy load_map(const std::string& path) {
  const toml::table root = read_toml(path, "map file");
  const TomlReader in(path);
  in.only(root, "",
          {"title", "case", "params", "escapement", "accuracy", "first", "second", "orbits",
           "equilibria", "marks"});
  MapStudy s;
  s.path = path;
  s.name = std::filesystem::path(path).stem().string();
  s.title = root.get("title") ? in.string(*root.get("title"), "title") : s.name;
  const toml::node* c = root.get("case");
  if (!c) throw InputError(path + ": key 'case' is missing");
  s.case_path = (std::filesystem::path(path).parent_path() / in.string(*c, "case"))
                    .lexically_normal()
                    .string();
  if (root.get("params")) s.params = in.string(*root.get("params"), "params");
  s.escapement = read_escapement_key(in, root);
  if (const toml::node* n = root.get("accuracy")) {
    const std::string text = in.string(*n, "accuracy");
    if (text != "fast" && text != "default" && text != "high")
      in.fail(*n, "accuracy", "\"fast\", \"default\" or \"high\"");
    s.accuracy = parse_accuracy(text, "accuracy");
  }
  s.first = read_axis(in, root, "first");
  s.second = read_axis(in, root, "second");
  if (s.first.parameter == s.second.parameter)
    in.fail(*root.get("second"), "second.parameter", "a parameter other than first.parameter");
  if ((s.first.points == 0) != (s.second.points == 0))
    in.fail(*root.get("second"), "second.points", "0 on both axes or on neither");
  const toml::node* list = root.get("orbits");
  const toml::node* equilibria = root.get("equilibria");
  if (!list && !equilibria)
    throw InputError(path +
                     ": key 'orbits' is missing; expected [[orbits]] tables, "
                     "[[equilibria]] tables or both");
  std::set<std::string> names;
  const auto entries = [&](const toml::node* n, const std::string& key) {
    if (n && (!n->is_array_of_tables() || n->as_array()->empty()))
      in.fail(*n, key, "one or more [[" + key + "]] tables");
    return n ? n->as_array() : nullptr;
  };
  int index = 0;
  if (const toml::array* orbits = entries(list, "orbits"))
    for (const auto& entry : *orbits) {
      const std::string prefix = "orbits[" + std::to_string(++index) + "].";
      const auto& t = *entry.as_table();
      in.only(t, prefix, {"name", "start", "at", "parent", "from_point"});
      MapOrbit o;
      read_entry(in, s, entry, prefix, names, o);
      s.orbits.push_back(o);
    }
  index = 0;
  if (const toml::array* list = entries(equilibria, "equilibria"))
    for (const auto& entry : *list) {
      const std::string prefix = "equilibria[" + std::to_string(++index) + "].";
      const auto& t = *entry.as_table();
      in.only(t, prefix, {"name", "start", "at", "parent", "from_point"});
      MapEquilibria e;
      read_entry(in, s, entry, prefix, names, e);
      s.equilibria.push_back(e);
    }
  if (const toml::node* n = root.get("marks")) {
    if (!n->is_array()) in.fail(*n, "marks", "a list of the case's parameter sets");
    for (const auto& m : *n->as_array()) s.marks.push_back(in.string(m, "marks"));
  }
  return s;
}

}  // namespace sympathy::app
