#include "cases/app/basins_file.hpp"

#include <toml++/toml.h>

#include <filesystem>

#include "sympathy/cases/toml_reader.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy::app {

namespace {

// The key of a BasinOptions field, as the file names it (grids counted from 1, as [[grid]]
// tables are read).
std::string key_of(const std::string& field) {
  if (field.rfind("grid[", 0) == 0) {
    const auto close = field.find(']');
    return "grid[" + std::to_string(std::stoi(field.substr(5, close - 5)) + 1) +
           field.substr(close);
  }
  if (field == "angle_min" || field == "angle_max") return "angles";
  if (field.rfind("flow.", 0) == 0) return field.substr(5) + " (the integrator's)";
  return field;
}

}  // namespace

bool is_basins_file(const std::string& path) {
  try {
    return read_toml(path, "study file").contains("case");
  } catch (const std::exception&) {
    return false;
  }
}

BasinsFile load_basins_file(const std::string& path) {
  const toml::table root = read_toml(path, "basins study file");
  const TomlReader in(path);
  in.only(root, "",
          {"title", "case", "params", "set", "initial", "grid", "starts", "angles", "seed", "t_end",
           "dt", "classifier", "confirm", "early_stop"});
  BasinsFile f;
  f.path = path;
  BasinOptions& o = f.options;
  const auto required = [&](const char* key) -> const toml::node& {
    const toml::node* n = root.get(key);
    if (!n) throw InputError(path + ": key '" + key + "' is missing");
    return *n;
  };
  f.title = root.get("title") ? in.string(*root.get("title"), "title")
                              : std::filesystem::path(path).stem().string();
  const std::string case_file = in.string(required("case"), "case");
  f.case_path = (std::filesystem::path(path).parent_path() / case_file).lexically_normal().string();
  if (const auto* n = root.get("params")) f.params = in.string(*n, "params");
  for (const char* group : {"set", "initial"}) {
    const toml::node* n = root.get(group);
    if (!n) continue;
    if (!n->is_table()) in.fail(*n, group, "a table of NAME = VALUE");
    for (auto&& [k, v] : *n->as_table()) {
      const std::string key = std::string(group) + "." + std::string(k.str());
      Assignment a{std::string(k.str()), in.number(v, key), in.where(v) + ": key '" + key + "'"};
      (std::string(group) == "set" ? f.sets : f.initial).push_back(a);
    }
  }
  const toml::node& grid = required("grid");
  if (!grid.is_array_of_tables() || grid.as_array()->empty())
    in.fail(grid, "grid", "one or two [[grid]] tables");
  int index = 0;
  for (const auto& entry : *grid.as_array()) {
    const std::string prefix = "grid[" + std::to_string(++index) + "].";
    const auto& t = *entry.as_table();
    in.only(t, prefix, {"parameter", "from", "to", "count", "value"});
    GridAxis a;
    if (!t.get("parameter"))
      throw InputError(in.where(entry) + ": key '" + prefix + "parameter' is missing");
    a.parameter = in.string(*t.get("parameter"), prefix + "parameter");
    if (const auto* v = t.get("value")) {  // one value
      if (t.get("from") || t.get("to") || t.get("count"))
        in.fail(*v, prefix + "value", "either value or from, to and count");
      a.from = a.to = in.number(*v, prefix + "value");
      a.count = 1;
    } else {
      for (const char* key : {"from", "to", "count"})
        if (!t.get(key))
          throw InputError(in.where(entry) + ": key '" + prefix + key + "' is missing");
      a.from = in.number(*t.get("from"), prefix + "from");
      a.to = in.number(*t.get("to"), prefix + "to");
      a.count = in.integer(*t.get("count"), prefix + "count");
    }
    o.grid.push_back(a);
  }
  if (const auto* n = root.get("starts")) o.starts = in.integer(*n, "starts");
  if (const auto* n = root.get("angles")) {
    const auto* list = n->as_array();
    if (!list || list->size() != 2) in.fail(*n, "angles", "[MIN, MAX] in rad");
    o.angle_min = in.number(*list->get(0), "angles[1]");
    o.angle_max = in.number(*list->get(1), "angles[2]");
  }
  if (const auto* n = root.get("seed")) {
    const int seed = in.integer(*n, "seed");
    if (seed < 0) in.fail(*n, "seed", "a non-negative integer");
    o.seed = static_cast<std::uint64_t>(seed);
  }
  if (const auto* n = root.get("t_end")) o.t_end = in.number(*n, "t_end");
  if (const auto* n = root.get("confirm")) {
    if (!n->is_boolean()) in.fail(*n, "confirm", "true or false");
    o.confirm = **n->as_boolean();
  }
  if (const auto* n = root.get("early_stop")) {
    if (!n->is_boolean()) in.fail(*n, "early_stop", "true or false");
    o.early_stop = **n->as_boolean();
  }
  if (const auto* n = root.get("dt")) o.dt = in.number(*n, "dt");
  if (const auto* n = root.get("classifier")) {
    const auto& t = in.table(*n, "classifier");
    in.only(t, "classifier.", {"window", "phase_tolerance", "lock_tolerance"});
    if (const auto* v = t.get("window")) o.classifier.window = in.number(*v, "classifier.window");
    if (const auto* v = t.get("phase_tolerance"))
      o.classifier.phase_tolerance = in.number(*v, "classifier.phase_tolerance");
    if (const auto* v = t.get("lock_tolerance"))
      o.classifier.lock_tolerance = in.number(*v, "classifier.lock_tolerance");
  }
  // The engine's own validation, as the command line's, named by key and located at the key's
  // line (a field's TOML path is its name, grids counted from 0: grid[0].count); a value that is
  // wrong only against another's default (t_end against the window) is located at the file.
  if (const auto problem = o.validate()) {
    std::string at = problem->field;
    if (at == "angle_min" || at == "angle_max") at = "angles";
    const toml::node* node = root.at_path(at).node();
    throw InputError((node ? in.where(*node) : path) + ": key '" + key_of(problem->field) +
                     "': expected " + problem->expected);
  }
  return f;
}

}  // namespace sympathy::app
