#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/names.hpp"
#include "sympathy/cases/toml_reader.hpp"
#include "sympathy/core/text.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <sstream>

namespace sympathy {

namespace {

Relation parse_relation(const std::string& text, const std::vector<std::string>& positions,
                        const std::function<void(const std::string&)>& fail) {
  std::string s;
  for (char ch : text)
    if (!std::isspace(static_cast<unsigned char>(ch))) s += ch;
  const auto eq = s.find('=');
  if (eq == std::string::npos) fail("a relation 'a = b', 'a = -b' or 'a = 0'");
  Relation r;
  r.component = s.substr(0, eq);
  std::string rhs = s.substr(eq + 1);
  auto known = [&](const std::string& name) {
    return std::find(positions.begin(), positions.end(), name) != positions.end();
  };
  if (!known(r.component))
    fail("a relation between positions (" + join(positions) + "), not '" + r.component + "'");
  if (rhs == "0") return r;
  if (!rhs.empty() && rhs[0] == '-') {
    r.sign = -1.0;
    rhs = rhs.substr(1);
  }
  if (!known(rhs) || rhs == r.component)
    fail("a relation between two different positions (" + join(positions) + ")");
  r.other = rhs;
  return r;
}

}  // namespace

Assignment parse_assignment(const std::string& text, const std::string& option) {
  const auto eq = text.find('=');
  Assignment a;
  a.source = option + " " + text;
  if (eq == std::string::npos || eq == 0)
    throw InputError(option + " " + text + ": expected KEY=VALUE");
  a.key = text.substr(0, eq);
  const std::string value = text.substr(eq + 1);
  const auto x = finite_number(value);
  if (!x)
    throw InputError(option + " " + text + ": expected a finite number after '" + a.key +
                     "=', got '" + value + "'");
  a.value = *x;
  return a;
}

CaseFile CaseFile::load(const std::string& path) {
  const toml::table root = read_toml(path, "case file");
  TomlReader in(path);
  CaseFile c;
  c.path_ = path;
  c.name_ = std::filesystem::path(path).stem().string();
  // An equation case file (kind = "equations") is read by EquationCase (equation_case.hpp).
  if (const auto* kind = root.get("kind")) {
    const std::string k = in.string(*kind, "kind");
    if (k == "equations")
      in.fail(*kind, "kind",
              "a metronome case file here (this command reads only those for now; simulate, "
              "orbit, continue, equilibria, curve and study read equation case files)");
    if (k != "metronomes") in.fail(*kind, "kind", "\"equations\" or \"metronomes\"");
  }
  in.only(root, "",
          {"kind", "name", "description", "escapement", "g", "default_params", "platform",
           "metronome", "metronomes", "springs", "params", "starts"});
  auto record = [&](const std::string& name, const toml::node& node, const std::string& key) {
    c.provenance_.emplace_back(name, in.where(node) + ": key '" + key + "'");
  };

  if (auto* n = root.get("name")) c.name_ = in.string(*n, "name");
  if (auto* n = root.get("description")) c.description_ = in.string(*n, "description");
  if (auto* n = root.get("escapement")) {
    const auto e = escapement_named(in.string(*n, "escapement"));
    if (!e) in.fail(*n, "escapement", "\"half\", \"double\" or \"impulsive\"");
    c.base_.escapement = *e;
  }
  if (auto* n = root.get("g")) {
    c.base_.g = in.number(*n, "g");
    record("g", *n, "g");
  }

  // Platform: its degrees of freedom, and M, c, k unless a parameter set gives them.
  c.base_.M = c.base_.cx = c.base_.cy = c.base_.kx = c.base_.ky = std::nan("");
  if (auto* n = root.get("platform")) {
    const auto& t = in.table(*n, "platform");
    in.only(t, "platform.", {"directions", "M", "c", "k", "cx", "cy", "kx", "ky"});
    if (auto* d = t.get("directions")) {
      if (!d->is_integer() || (*d->value<int64_t>() != 1 && *d->value<int64_t>() != 2))
        in.fail(*d, "platform.directions", "1 (x) or 2 (x and y)");
      c.base_.directions = static_cast<int>(*d->value<int64_t>());
    }
    for (auto&& [key, node] : t) {
      const std::string k(key.str());
      if (k == "directions") continue;
      if ((k == "cx" || k == "cy" || k == "kx" || k == "ky") && c.base_.directions != 2)
        in.fail(static_cast<int>(key.source().begin.line), "platform." + k,
                "only c and k on a 1-D platform (directions = 1)");
      c.base_.set(k, in.number(node, "platform." + k));
      record(k, node, "platform." + k);
    }
  }

  // Metronomes: shared values in [metronome], one [[metronomes]] entry each, with overrides.
  std::map<std::string, double> shared{{"angle", 0.0}};
  std::map<std::string, const toml::node*> shared_nodes;
  if (auto* n = root.get("metronome")) {
    const auto& t = in.table(*n, "metronome");
    in.only(t, "metronome.", metronome_keys());
    for (auto&& [key, node] : t) {
      const std::string k(key.str());
      shared[k] = in.number(node, "metronome." + k);
      shared_nodes[k] = &node;
    }
  }
  const auto* list = root.get("metronomes");
  if (list == nullptr)
    throw InputError(path +
                     ": key 'metronomes' is missing: expected one [[metronomes]] table "
                     "per metronome");
  if (!list->is_array_of_tables() || list->as_array()->empty())
    in.fail(*list, "metronomes", "one [[metronomes]] table per metronome");
  int index = 0;
  for (const auto& entry : *list->as_array()) {
    ++index;
    const std::string prefix = "metronomes[" + std::to_string(index) + "].";
    const auto& t = *entry.as_table();
    in.only(t, prefix, metronome_keys());
    MetronomeSpec m;
    for (const auto& key : metronome_keys()) {
      const std::string id = key + std::to_string(index);
      if (auto* v = t.get(key)) {
        m.values[key] = in.number(*v, prefix + key);
        if (key != "angle") m.overridden.insert(key);
        record(id, *v, prefix + key);
      } else if (shared.count(key)) {
        m.values[key] = shared[key];
        if (shared_nodes.count(key)) record(id, *shared_nodes[key], "metronome." + key);
      } else {
        throw InputError(in.where(entry) + ": key '" + prefix + key +
                         "' is missing: expected it in [metronome] (shared) or in every "
                         "[[metronomes]] entry");
      }
    }
    c.base_.metronomes.push_back(std::move(m));
  }

  if (auto* n = root.get("springs")) {
    if (!n->is_array_of_tables()) in.fail(*n, "springs", "[[springs]] tables");
    int j = 0;
    for (const auto& entry : *n->as_array()) {
      ++j;
      const std::string prefix = "springs[" + std::to_string(j) + "].";
      const auto& t = *entry.as_table();
      in.only(t, prefix, {"between", "kappa"});
      const auto* between = t.get("between");
      const auto* kappa = t.get("kappa");
      if (!between || !kappa)
        throw InputError(in.where(entry) + ": key '" + prefix + (between ? "kappa" : "between") +
                         "' is missing: expected between = [i, j] (1-based metronome numbers) "
                         "and kappa (N m/rad)");
      const int count = static_cast<int>(c.base_.metronomes.size());
      const auto* arr = between->as_array();
      if (!arr || arr->size() != 2 || !(*arr)[0].is_integer() || !(*arr)[1].is_integer())
        in.fail(*between, prefix + "between", "two metronome numbers [i, j]");
      // Checked as 64-bit integers, before narrowing: any number the file holds is in range.
      const int64_t first = *(*arr)[0].value<int64_t>();
      const int64_t second = *(*arr)[1].value<int64_t>();
      if (first < 1 || first > count || second < 1 || second > count || first == second)
        in.fail(*between, prefix + "between",
                "two different metronomes among 1.." + std::to_string(count));
      SpringSpec s;
      s.first = static_cast<int>(first) - 1;
      s.second = static_cast<int>(second) - 1;
      s.kappa = in.number(*kappa, prefix + "kappa");
      record("kappa" + std::to_string(j), *kappa, prefix + "kappa");
      c.base_.springs.push_back(s);
    }
  }

  // Parameter sets: any parameter name of the model.
  const auto names = c.base_.parameter_names();
  if (auto* n = root.get("params")) {
    const auto& sets = in.table(*n, "params");
    for (auto&& [set_name, set_node] : sets) {
      const std::string prefix = "params." + std::string(set_name.str()) + ".";
      const auto& t = in.table(set_node, prefix.substr(0, prefix.size() - 1));
      ParameterSet ps;
      ps.name = std::string(set_name.str());
      ps.line = static_cast<int>(set_node.source().begin.line);
      for (auto&& [key, node] : t) {
        const std::string k(key.str());
        if (!c.base_.has_parameter(k))
          in.fail(static_cast<int>(key.source().begin.line), prefix + k,
                  "a parameter of the model (" + join(names) + ")");
        ps.entries.push_back(
            {k, in.number(node, prefix + k), static_cast<int>(node.source().begin.line)});
      }
      c.parameter_sets_.push_back(std::move(ps));
    }
  }
  if (auto* n = root.get("default_params")) {
    c.default_params_ = in.string(*n, "default_params");
    const auto sets = c.parameter_set_names();
    if (std::find(sets.begin(), sets.end(), c.default_params_) == sets.end())
      in.fail(*n, "default_params", "the name of a [params.NAME] table (" + join(sets) + ")");
  }

  // Starts: state values and the invariant subspace the start lies in.
  const auto states = c.state_names();
  const std::vector<std::string> positions(states.begin(), states.begin() + states.size() / 2);
  if (auto* n = root.get("starts")) {
    const auto& starts = in.table(*n, "starts");
    for (auto&& [start_name, start_node] : starts) {
      const std::string prefix = "starts." + std::string(start_name.str()) + ".";
      const auto& t = in.table(start_node, prefix.substr(0, prefix.size() - 1));
      StartSpec s;
      s.name = std::string(start_name.str());
      s.source = in.where(start_node);
      auto allowed = states;
      allowed.push_back("invariant");
      in.only(t, prefix, allowed);
      for (auto&& [key, node] : t) {
        const std::string k(key.str());
        if (k == "invariant") {
          const auto* arr = node.as_array();
          if (!arr) in.fail(node, prefix + k, "an array of relations such as \"th2 = -th1\"");
          for (const auto& rel : *arr) {
            const std::string text = in.string(rel, prefix + k);
            s.invariant.push_back(parse_relation(text, positions, [&](const std::string& what) {
              in.fail(static_cast<int>(rel.source().begin.line), prefix + k, what,
                      "\"" + text + "\"");
            }));
          }
        } else {
          s.values.emplace_back(k, in.number(node, prefix + k));
        }
      }
      c.starts_.push_back(std::move(s));
    }
  }
  // Tables iterate in key order; keep the file's order for listings and help texts.
  auto line_of = [](const std::string& where) {
    return std::stoi(where.substr(where.rfind(':') + 1));
  };
  std::stable_sort(c.starts_.begin(), c.starts_.end(), [&](const auto& a, const auto& b) {
    return line_of(a.source) < line_of(b.source);
  });
  std::stable_sort(c.parameter_sets_.begin(), c.parameter_sets_.end(),
                   [](const auto& a, const auto& b) { return a.line < b.line; });

  // Everything the file gives alone must already make sense (M, c, k may come from a set).
  for (const auto& [param, expected] : c.base_.problems()) {
    if (param == "M" || param == "c" || param == "k" || param == "cx" || param == "cy" ||
        param == "kx" || param == "ky")
      continue;
    for (auto it = c.provenance_.rbegin(); it != c.provenance_.rend(); ++it)
      if (it->first == param) throw InputError(it->second + ": expected " + expected);
    throw InputError(path + ": parameter '" + param + "': expected " + expected);
  }
  return c;
}

std::vector<std::string> CaseFile::parameter_set_names() const {
  std::vector<std::string> names;
  for (const auto& s : parameter_sets_) names.push_back(s.name);
  return names;
}

std::vector<std::string> CaseFile::start_names() const {
  std::vector<std::string> names;
  for (const auto& s : starts_) names.push_back(s.name);
  return names;
}

std::vector<std::string> CaseFile::state_names() const {
  std::vector<std::string> names{"x"};
  if (base_.directions == 2) names.push_back("y");
  for (std::size_t i = 0; i < base_.metronomes.size(); ++i)
    names.push_back("th" + std::to_string(i + 1));
  const std::size_t m = names.size();
  for (std::size_t i = 0; i < m; ++i) names.push_back("v" + names[i]);
  return names;
}

ModelSpec CaseFile::spec(const std::string& params, const std::vector<Assignment>& sets) const {
  ModelSpec spec = base_;
  auto provenance = provenance_;
  const std::string chosen = params.empty() ? default_params_ : params;
  if (!chosen.empty()) {
    auto it = std::find_if(parameter_sets_.begin(), parameter_sets_.end(),
                           [&](const auto& s) { return s.name == chosen; });
    if (it == parameter_sets_.end())
      throw InputError("--params " + chosen + ": no parameter set '" + chosen + "' in " + path_ +
                       "; expected one of: " + join(parameter_set_names()));
    for (const auto& e : it->entries) {
      spec.set(e.key, e.value);
      provenance.emplace_back(e.key, path_ + ":" + std::to_string(e.line) + ": key 'params." +
                                         chosen + "." + e.key + "'");
    }
  }
  for (const auto& a : sets) {
    if (!spec.has_parameter(a.key))
      throw InputError(a.source + ": unknown parameter '" + a.key +
                       "'; expected one of: " + join(spec.parameter_names()));
    spec.set(a.key, a.value);
    provenance.emplace_back(a.key, a.source);
  }
  const auto problems = spec.problems();
  if (!problems.empty()) {
    const auto& [param, expected] = problems.front();
    // Name the last place that set this value: its own name, or the shared name it follows.
    std::string base = param;
    while (!base.empty() && std::isdigit(static_cast<unsigned char>(base.back()))) base.pop_back();
    if (base == "cx" || base == "cy") base = "c";
    if (base == "kx" || base == "ky") base = "k";
    for (auto it = provenance.rbegin(); it != provenance.rend(); ++it)
      if (it->first == param || it->first == base)
        throw InputError(it->second + ": expected " + expected + ", got " +
                         format_number(spec.get(param)));
    throw InputError(path_ + ": no value for parameter '" + param + "': give it in the file " +
                     "(e.g. [platform] or a [params.NAME] set) or with --set " + param +
                     "=VALUE; expected " + expected);
  }
  return spec;
}

const StartSpec& CaseFile::start(const std::string& name) const {
  for (const auto& s : starts_)
    if (s.name == name) return s;
  throw InputError("--start " + name + ": no start '" + name + "' in " + path_ +
                   "; expected one of: " + join(start_names()));
}

namespace {

// A start that ties metronomes in phase (thJ = thI, nothing else) declares the fixed space of
// permuting them: identical metronomes (checked where it is used, PermutationSymmetry::defect,
// at the parameter values of the run) then move alike on it, and an orbit there can be computed
// for the cost of two of them (continuation/symmetry_reduction.hpp).
InvariantSubspace with_metronome_symmetry(const InvariantSubspace& subspace, const StartSpec& start,
                                          const std::vector<std::string>& names) {
  const int n = static_cast<int>(names.size());
  std::vector<int> angles;
  auto angle = [&](const std::string& name) {
    const auto it = std::find(names.begin(), names.end(), name);
    return name.rfind("th", 0) == 0 && it != names.end() ? static_cast<int>(it - names.begin())
                                                         : -1;
  };
  for (const auto& r : start.invariant) {
    const int a = angle(r.component), b = r.other.empty() ? -1 : angle(r.other);
    if (a < 0 || b < 0 || r.sign != 1.0) return subspace;
    for (int c : {a, b})
      if (std::find(angles.begin(), angles.end(), c) == angles.end()) angles.push_back(c);
  }
  if (angles.size() < 3) return subspace;
  std::sort(angles.begin(), angles.end());
  PermutationSymmetry symmetry;
  std::vector<int> numbers;
  for (int c : angles) {
    symmetry.units.push_back({c, c + n / 2});  // the angle and its velocity
    numbers.push_back(std::stoi(names[c].substr(2)));
  }
  // "1-64", or "1-3, 5": runs of consecutive numbers.
  std::string list;
  std::sort(numbers.begin(), numbers.end());
  for (std::size_t i = 0; i < numbers.size();) {
    std::size_t j = i;
    while (j + 1 < numbers.size() && numbers[j + 1] == numbers[j] + 1) ++j;
    list += (list.empty() ? "" : ", ") + std::to_string(numbers[i]) +
            (j > i ? "-" + std::to_string(numbers[j]) : "");
    i = j + 1;
  }
  symmetry.description = "metronomes " + list;
  try {
    return subspace.with_symmetry(std::move(symmetry), n);
  } catch (const std::invalid_argument&) {
    return subspace;  // ties that leave some of them apart: no permutation symmetry
  }
}

}  // namespace

InvariantSubspace CaseFile::invariant_subspace(const StartSpec& start,
                                               const OdeSystem& system) const {
  const auto names = state_names();
  const int n = static_cast<int>(names.size());
  auto index = [&](const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  std::vector<ComponentRelation> relations;
  std::string text;
  for (const auto& r : start.invariant) {
    const int a = index(r.component);
    const int b = r.other.empty() ? -1 : index(r.other);
    relations.push_back({a, b, r.sign});                               // positions
    relations.push_back({a + n / 2, b < 0 ? -1 : b + n / 2, r.sign});  // their velocities
    text += (text.empty() ? "" : ", ") + r.component + " = " +
            (r.other.empty() ? "0" : (r.sign < 0 ? "-" : "") + r.other);
  }
  InvariantSubspace subspace =
      with_metronome_symmetry(InvariantSubspace(n, relations, text), start, names);
  const double defect = subspace.invariance_defect(system, system.default_parameters(),
                                                   Eigen::VectorXd::Constant(n, 0.5));
  if (defect > 1e-12)
    throw InputError(start.source + ": start '" + start.name +
                     "': the model does not keep the "
                     "subspace {" +
                     text + "} invariant (relative defect " + format_number(defect) +
                     "); expected relations that a symmetry of the "
                     "model keeps, or no 'invariant' key");
  return subspace;
}

Eigen::VectorXd CaseFile::initial_state(const StartSpec* start,
                                        const std::vector<Assignment>& initial) const {
  const auto names = state_names();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(static_cast<int>(names.size()));
  auto index_of = [&](const std::string& name, const std::string& source) {
    auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
      throw InputError(source + ": unknown state '" + name + "'; expected one of: " + join(names));
    return static_cast<int>(it - names.begin());
  };
  if (start)
    for (const auto& [name, value] : start->values) z[index_of(name, start->source)] = value;
  for (const auto& a : initial) z[index_of(a.key, a.source)] = a.value;
  return z;
}

}  // namespace sympathy
