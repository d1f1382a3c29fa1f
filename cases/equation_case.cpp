#include "sympathy/cases/equation_case.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <sstream>

#include <toml++/toml.h>

#include "sympathy/cases/names.hpp"
#include "sympathy/cases/toml_reader.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy {

namespace {

// C++ keywords and alternative tokens (C++20): never a name, even though generated code names
// nothing after the file (it uses s0, p0, w0, ...): a name may reach other tools' code later.
constexpr std::array<std::string_view, 97> kKeywords{
    "alignas",       "alignof",     "and",
    "and_eq",        "asm",         "auto",
    "bitand",        "bitor",       "bool",
    "break",         "case",        "catch",
    "char",          "char8_t",     "char16_t",
    "char32_t",      "class",       "compl",
    "concept",       "const",       "consteval",
    "constexpr",     "constinit",   "const_cast",
    "continue",      "co_await",    "co_return",
    "co_yield",      "decltype",    "default",
    "delete",        "do",          "double",
    "dynamic_cast",  "else",        "enum",
    "explicit",      "export",      "extern",
    "false",         "float",       "for",
    "friend",        "goto",        "if",
    "inline",        "int",         "long",
    "mutable",       "namespace",   "new",
    "noexcept",      "not",         "not_eq",
    "nullptr",       "operator",    "or",
    "or_eq",         "private",     "protected",
    "public",        "register",    "reinterpret_cast",
    "requires",      "return",      "short",
    "signed",        "sizeof",      "static",
    "static_assert", "static_cast", "struct",
    "switch",        "template",    "this",
    "thread_local",  "throw",       "true",
    "try",           "typedef",     "typeid",
    "typename",      "union",       "unsigned",
    "using",         "virtual",     "void",
    "volatile",      "wchar_t",     "while",
    "xor",           "xor_eq",      "final",
    "override",      "import",      "module",
    "main",
};

bool is_keyword(std::string_view name) {
  return std::find(kKeywords.begin(), kKeywords.end(), name) != kKeywords.end();
}

// The file's bytes; refused when too long or not printable ASCII (tabs and line ends allowed),
// before TOML sees it: a message then never echoes bytes a terminal could misread, and columns
// count bytes.
std::string read_ascii(const std::string& path) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path + ": cannot read the case file (no such file)");
  const auto size = std::filesystem::file_size(path);
  if (size > kMaxEquationFileBytes)
    throw InputError(path + ": expected an equation case file of at most " +
                     std::to_string(kMaxEquationFileBytes) + " bytes, got " + std::to_string(size));
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  const std::string s = text.str();
  int line = 1, column = 1;
  for (char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '\n') {
      ++line;
      column = 1;
      continue;
    }
    if (c >= 0x80 || (c < 0x20 && c != '\t' && c != '\r') || c == 0x7f) {
      static const char* hex = "0123456789abcdef";
      throw InputError(path + ":" + std::to_string(line) + ":" + std::to_string(column) +
                       ": expected ASCII text (an equation case file is ASCII throughout, "
                       "comments included), got byte 0x" +
                       hex[c >> 4] + hex[c & 15]);
    }
    ++column;
  }
  return s;
}

class Loader {
 public:
  Loader(std::string path, std::string text) : in_(path), path_(std::move(path)) {
    std::size_t start = 0;
    for (;;) {
      line_starts_.push_back(start);
      const auto nl = text.find('\n', start);
      if (nl == std::string::npos) break;
      start = nl + 1;
    }
    text_ = std::move(text);
  }

  const TomlReader& in() const { return in_; }

  std::string where(const toml::node& node) const {
    return path_ + ":" + std::to_string(node.source().begin.line) + ":" +
           std::to_string(node.source().begin.column);
  }
  std::string where_key(const toml::key& key) const {
    return path_ + ":" + std::to_string(key.source().begin.line) + ":" +
           std::to_string(key.source().begin.column);
  }
  [[noreturn]] void fail_key(const toml::key& key, const std::string& full_key,
                             const std::string& expected, const std::string& got) const {
    throw InputError(where_key(key) + ": key '" + full_key + "': expected " + expected +
                     (got.empty() ? "" : ", got " + got));
  }

  // A name of the file: checked as the header says.
  void check_name(const toml::key& key, const std::string& full_key) const {
    const std::string name(key.str());
    auto bad = [&](const std::string& what) {
      fail_key(key, full_key, "a name that " + what, "'" + name + "'");
    };
    if (name.empty()) bad("is not empty");
    if (name.size() > kMaxNameLength)
      fail_key(key, full_key, "a name of at most " + std::to_string(kMaxNameLength) + " characters",
               std::to_string(name.size()) + " characters");
    const char first = name[0];
    if (!((first >= 'a' && first <= 'z') || (first >= 'A' && first <= 'Z')))
      bad("starts with an ASCII letter");
    for (char c : name)
      if (!((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
        bad("has only ASCII letters, digits and '_'");
    if (name.find("__") != std::string::npos) bad("has no \"__\" (reserved in C++)");
    if (name == "t" || name == "pi") bad("is not built in (t is the time, pi the constant)");
    for (const auto& f : functions())
      if (f.name == name) bad("is not a function of the grammar");
    if (is_keyword(name)) bad("is not a C++ keyword");
    const auto it = defined_.find(name);
    if (it != defined_.end()) bad("is not defined twice (first at " + it->second + ")");
  }
  void define(const std::string& name, const std::string& where) { defined_[name] = where; }

  // An expression of the file, parsed, with an error located at its line and column.
  Expression expression(const toml::node& node, const std::string& full_key) const {
    if (!node.is_string())
      in_.fail(node, full_key, "an expression in quotes, such as \"-x + a*y\"");
    const std::string text(*node.value<std::string_view>());
    const std::size_t at = content_start(node);
    const std::string_view raw(text_);
    // Escapes (\u003b, a line-ending backslash) would shift every column after them, and an
    // expression needs none: the text must stand in the file as it is read.
    if (raw.substr(at, text.size()) != text) {
      const auto slash = raw.find('\\', at);
      throw InputError(location(slash == std::string::npos ? at : slash) + ": key '" + full_key +
                       "': expected an expression without escapes ('\\'), as it is meant");
    }
    try {
      return parse_expression(text);
    } catch (const ExpressionError& e) {
      throw InputError(location(at + e.offset) + ": key '" + full_key + "': " + e.message());
    }
  }

  // "FILE:LINE:COLUMN" of a byte of the file.
  std::string location(std::size_t byte) const {
    const auto it = std::upper_bound(line_starts_.begin(), line_starts_.end(), byte);
    const std::size_t line = static_cast<std::size_t>(it - line_starts_.begin());
    const std::size_t column = byte - line_starts_[line - 1] + 1;
    return path_ + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
  // Where an Expression node of the expression that starts at `node`'s text is.
  std::string location(const toml::node& node, std::size_t offset) const {
    return location(content_start(node) + offset);
  }

  // The byte where a string value's text starts in the file: after the opening quote(s), and
  // after the line break that TOML drops right after an opening triple quote.
  std::size_t content_start(const toml::node& node) const {
    const auto& pos = node.source().begin;
    std::size_t at = line_starts_.at(pos.line - 1) + pos.column - 1;
    const std::string_view raw(text_);
    const bool triple = raw.substr(at, 3) == "\"\"\"" || raw.substr(at, 3) == "'''";
    at += triple ? 3 : 1;
    if (triple && raw.substr(at, 1) == "\n") at += 1;
    if (triple && raw.substr(at, 2) == "\r\n") at += 2;
    return at;
  }

 private:
  TomlReader in_;
  std::string path_;
  std::string text_;
  std::vector<std::size_t> line_starts_;
  std::map<std::string, std::string> defined_;  // name -> where it is defined
};

// A table's entries in the order of the file (toml++ iterates in key order).
std::vector<std::pair<const toml::key*, const toml::node*>> in_file_order(const toml::table& t) {
  std::vector<std::pair<const toml::key*, const toml::node*>> entries;
  for (auto&& [key, node] : t) entries.emplace_back(&key, &node);
  std::stable_sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    const auto& pa = a.first->source().begin;
    const auto& pb = b.first->source().begin;
    return pa.line != pb.line ? pa.line < pb.line : pa.column < pb.column;
  });
  return entries;
}

}  // namespace

std::string case_file_kind(const std::string& path) {
  const toml::table root = read_toml(path, "case file");
  const auto* kind = root.get("kind");
  if (kind == nullptr) return "metronomes";
  TomlReader in(path);
  const std::string k = in.string(*kind, "kind");
  if (k != "equations" && k != "metronomes")
    in.fail(*kind, "kind", "\"equations\" or \"metronomes\" (the default)");
  return k;
}

EquationCase EquationCase::load(const std::string& path) {
  std::string text = read_ascii(path);
  const toml::table root = parse_toml(text, path);
  Loader loader(path, std::move(text));
  const TomlReader& in = loader.in();
  EquationCase c;
  c.path_ = path;
  c.name_ = std::filesystem::path(path).stem().string();
  in.only(
      root, "",
      {"kind", "name", "description", "plugin", "states", "parameters", "intermediates",
       "equations", "steep", "impacts", "forcing_period", "params", "default_params", "starts"});
  const auto* kind = root.get("kind");
  if (kind == nullptr || in.string(*kind, "kind") != "equations")
    throw InputError(path +
                     ": key 'kind' is missing: expected kind = \"equations\" in an "
                     "equation case file");
  if (auto* n = root.get("name")) c.name_ = in.string(*n, "name");
  if (auto* n = root.get("description")) c.description_ = in.string(*n, "description");
  auto required = [&](const char* key, const char* what) -> const toml::table& {
    const auto* n = root.get(key);
    if (n == nullptr)
      throw InputError(path + ": table [" + std::string(key) + "] is missing: expected " + what);
    const auto& t = in.table(*n, key);
    if (t.empty()) in.fail(*n, key, what);
    return t;
  };

  auto& sys = c.system_;
  // States and parameters first: every later expression may use them.
  for (const auto& [key, node] : in_file_order(required(
           "states",
           "one entry per state, NAME = initial value, or NAME = { value = V, angle = true }"))) {
    const std::string full = "states." + std::string(key->str());
    loader.check_name(*key, full);
    EquationState state{std::string(key->str()), 0.0, false};
    if (node->is_table()) {
      const auto& t = *node->as_table();
      in.only(t, full + ".", {"value", "angle"});
      const auto* value = t.get("value");
      if (value == nullptr)
        throw InputError(in.where(*node) + ": key '" + full +
                         ".value' is missing: expected the state's initial value");
      state.initial = in.number(*value, full + ".value");
      if (const auto* a = t.get("angle")) {
        if (!a->is_boolean()) in.fail(*a, full + ".angle", "true or false");
        state.angle = a->as_boolean()->get();
      }
    } else {
      state.initial = in.number(*node, full);
    }
    sys.states.push_back(std::move(state));
    loader.define(sys.states.back().name, loader.where_key(*key));
  }
  if (const auto* n = root.get("parameters")) {
    for (const auto& [key, node] : in_file_order(in.table(*n, "parameters"))) {
      const std::string full = "parameters." + std::string(key->str());
      loader.check_name(*key, full);
      EquationParameter p;
      p.name = std::string(key->str());
      p.source = in.where(*node) + ": key '" + full + "'";
      if (node->is_table()) {
        const auto& t = *node->as_table();
        in.only(t, full + ".", {"value", "unit", "min", "max"});
        const auto* value = t.get("value");
        if (value == nullptr)
          throw InputError(in.where(*node) + ": key '" + full +
                           ".value' is missing: expected the parameter's value");
        p.value = in.number(*value, full + ".value");
        if (const auto* u = t.get("unit")) p.unit = in.string(*u, full + ".unit");
        if (const auto* m = t.get("min")) p.min = in.number(*m, full + ".min");
        if (const auto* m = t.get("max")) p.max = in.number(*m, full + ".max");
        if (p.min && p.max && *p.min > *p.max)
          in.fail(*t.get("max"), full + ".max", "at least min = " + format_number(*p.min));
        if ((p.min && p.value < *p.min) || (p.max && p.value > *p.max))
          in.fail(*value, full + ".value",
                  "a value within [" + (p.min ? format_number(*p.min) : "-inf") + ", " +
                      (p.max ? format_number(*p.max) : "inf") + "]");
      } else {
        p.value = in.number(*node, full);
      }
      sys.parameters.push_back(std::move(p));
      loader.define(sys.parameters.back().name, loader.where_key(*key));
    }
  }

  // Names an expression may use: built-ins, states, parameters, intermediates defined so far.
  std::map<std::string, std::string> usable{{"t", ""}, {"pi", ""}};
  for (const auto& s : sys.states) usable[s.name] = "state";
  for (const auto& p : sys.parameters) usable[p.name] = "parameter";
  std::map<std::string, std::string> later;  // intermediates not yet usable -> where defined
  const toml::table* intermediates = nullptr;
  if (const auto* n = root.get("intermediates")) {
    intermediates = &in.table(*n, "intermediates");
    for (const auto& [key, node] : in_file_order(*intermediates)) {
      loader.check_name(*key, "intermediates." + std::string(key->str()));
      loader.define(std::string(key->str()), loader.where_key(*key));
      later[std::string(key->str())] = loader.where_key(*key);
    }
  }
  auto check_names = [&](const Expression& tree, const toml::node& node, const std::string& full,
                         const std::string& self = "") {
    std::vector<const Expression*> names;
    collect_names(tree, names);
    for (const auto* e : names) {
      if (e->name == "t") sys.uses_time = true;
      if (usable.count(e->name)) continue;
      const std::string at = loader.location(node, e->offset) + ": key '" + full + "': ";
      if (e->name == self)
        throw InputError(at + "expected names defined above this intermediate, got '" + self +
                         "' itself");
      if (later.count(e->name))
        throw InputError(at + "expected names defined above this intermediate, got '" + e->name +
                         "' (defined at " + later[e->name] + "; intermediates are evaluated " +
                         "in the order of the file)");
      std::vector<std::string> known;
      for (const auto& [name, what] : usable) known.push_back(name);
      throw InputError(at + "expected a state, a parameter, an intermediate, t or pi (" +
                       join(known) + "), got the unknown name '" + e->name + "'");
    }
  };
  if (intermediates != nullptr) {
    for (const auto& [key, node] : in_file_order(*intermediates)) {
      const std::string name(key->str());
      const std::string full = "intermediates." + name;
      Expression tree = loader.expression(*node, full);
      later.erase(name);
      check_names(tree, *node, full, name);  // its own name is not usable yet
      usable[name] = "intermediate";
      sys.intermediates.push_back({name, std::move(tree)});
    }
  }

  // A C++ plug-in instead of equations: its source beside the case file (or where it says).
  if (const auto* n = root.get("plugin")) {
    const std::string name = in.string(*n, "plugin");
    for (const char* table : {"intermediates", "equations", "steep", "impacts"})
      if (root.get(table) != nullptr)
        in.fail(*root.get(table), table,
                "no [" + std::string(table) + "] in a case file with a plug-in (its equations " +
                    "and steep zones are the plug-in's C++, " + name + ")");
    // A plain file name: letters, digits and _ . / - only (a newline or a quote in it has no
    // business in a path, and the name is shown in messages and reports).
    const auto plain = [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '.' || ch == '/' ||
             ch == '-';
    };
    if (!std::all_of(name.begin(), name.end(), plain))
      in.fail(*n, "plugin",
              "a file name of letters, digits and _ . / - only (no spaces, quotes or control "
              "characters)");
    const std::filesystem::path source =
        std::filesystem::path(path).parent_path() / std::filesystem::path(name);
    std::error_code ec;
    if (name.size() < 5 || name.substr(name.size() - 4) != ".cpp" ||
        !std::filesystem::is_regular_file(source, ec))
      in.fail(*n, "plugin",
              "the name of a C++ source file (.cpp) beside the case file or relative to it, got '" +
                  name + "'" + (std::filesystem::exists(source, ec) ? "" : " (no such file)"));
    if (std::filesystem::file_size(source, ec) > kMaxEquationFileBytes)
      in.fail(*n, "plugin", "a source of at most 1 MiB");
    c.plugin_ = source.string();
  }

  // One equation per state, in state order (none for a plug-in).
  if (c.plugin_.empty()) {
    const auto& equations = required("equations", "one expression per state, STATE = \"...\"");
    std::map<std::string, const toml::node*> by_state;
    for (const auto& [key, node] : in_file_order(equations)) {
      const std::string name(key->str());
      const bool is_state = std::any_of(sys.states.begin(), sys.states.end(),
                                        [&](const auto& s) { return s.name == name; });
      if (!is_state) {
        std::vector<std::string> states;
        for (const auto& s : sys.states) states.push_back(s.name);
        loader.fail_key(*key, "equations." + name,
                        "an equation for a state of [states] (" + join(states) + ")",
                        "'" + name + "', not a state");
      }
      by_state[name] = node;
    }
    for (const auto& s : sys.states) {
      const auto it = by_state.find(s.name);
      if (it == by_state.end())
        throw InputError(
            path + ":" + std::to_string(equations.source().begin.line) +
            ": table [equations]: expected an equation for every state, got none for '" + s.name +
            "' (give " + s.name + " = \"...\", its time derivative)");
      const std::string full = "equations." + s.name;
      Expression tree = loader.expression(*it->second, full);
      check_names(tree, *it->second, full);
      sys.derivatives.push_back({s.name, std::move(tree)});
    }
  }

  // An expression of the parameters alone (`why` says why: it does not change along the motion),
  // positive at the file's values.
  auto parameters_only = [&](const toml::node& at, const std::string& where, const char* why) {
    Expression tree = loader.expression(at, where);
    std::vector<const Expression*> names;
    collect_names(tree, names);
    for (const auto* e : names)
      if (e->name != "pi" && !(usable.count(e->name) && usable.at(e->name) == "parameter"))
        throw InputError(loader.location(at, e->offset) + ": key '" + where +
                         "': expected parameters, numbers and pi only (" + why + "), got '" +
                         e->name + "'");
    const double value = evaluate_expression(tree, [&](const std::string& v) {
      if (v == "pi") return std::numbers::pi;
      for (const auto& p : sys.parameters)
        if (p.name == v) return p.value;
      return 0.0;
    });
    if (!(value > 0.0) || !std::isfinite(value))
      in.fail(at, where,
              "a positive value at the file's parameter values, got " + format_number(value));
    return tree;
  };

  // Steep zones: per state, a width (and a scale) from the parameters alone, positive at the
  // file's values.
  if (const auto* n = root.get("steep")) {
    constexpr const char* kZoneSize = "a zone's size does not change along the motion";
    std::map<std::string, SteepSpec> by_state;
    for (const auto& [key, node] : in_file_order(in.table(*n, "steep"))) {
      const std::string name(key->str());
      const std::string full = "steep." + name;
      const auto state = std::find_if(sys.states.begin(), sys.states.end(),
                                      [&](const auto& st) { return st.name == name; });
      if (state == sys.states.end())
        loader.fail_key(*key, full, "a state of [states] (" + join(c.state_names()) + ")",
                        "'" + name + "', not a state");
      SteepSpec spec;
      spec.state = static_cast<int>(state - sys.states.begin());
      if (node->is_table()) {
        const auto& t = *node->as_table();
        in.only(t, full + ".", {"width", "scale"});
        const auto* width = t.get("width");
        if (width == nullptr)
          throw InputError(in.where(*node) + ": key '" + full +
                           ".width' is missing: expected the zone's half-width");
        spec.width = parameters_only(*width, full + ".width", kZoneSize);
        if (const auto* scale = t.get("scale"))
          spec.scale = parameters_only(*scale, full + ".scale", kZoneSize);
      } else {
        spec.width = parameters_only(*node, full, kZoneSize);
      }
      by_state[name] = std::move(spec);
    }
    for (const auto& st : sys.states)
      if (by_state.count(st.name)) sys.steep.push_back(std::move(by_state[st.name]));
  }

  // Impacts: a surface, the direction it is reached from, the states' values after it. Data like
  // the equations: each expression a checked tree that code generation writes out.
  if (const auto* n = root.get("impacts")) {
    if (!n->is_array_of_tables() || n->as_array()->empty())
      in.fail(*n, "impacts", "one or more [[impacts]] tables");
    int index = 0;
    for (const auto& entry : *n->as_array()) {
      const std::string prefix = "impacts[" + std::to_string(++index) + "].";
      const auto& t = *entry.as_table();
      in.only(t, prefix, {"surface", "direction", "reset"});
      ImpactSpec impact;
      const auto* surface = t.get("surface");
      if (surface == nullptr)
        throw InputError(in.where(entry) + ": key '" + prefix +
                         "surface' is missing: expected the impact surface h, an expression "
                         "(the impact where h = 0)");
      impact.surface = loader.expression(*surface, prefix + "surface");
      check_names(impact.surface, *surface, prefix + "surface");
      if (const auto* d = t.get("direction")) {
        const std::string text = in.string(*d, prefix + "direction");
        if (text != "decreasing" && text != "increasing")
          in.fail(*d, prefix + "direction",
                  "\"decreasing\" (the impact where h falls through 0, from h > 0) or "
                  "\"increasing\"");
        impact.direction = text == "increasing" ? 1 : -1;
      }
      const auto* reset = t.get("reset");
      if (reset == nullptr)
        throw InputError(in.where(entry) + ": key '" + prefix +
                         "reset' is missing: expected the states after the impact, { STATE = "
                         "\"...\" }");
      const auto& values = in.table(*reset, prefix + "reset");
      if (values.empty()) in.fail(*reset, prefix + "reset", "one or more STATE = \"...\"");
      std::map<std::string, const toml::node*> by_state;
      for (const auto& [key, node] : in_file_order(values)) {
        const std::string name(key->str());
        if (!std::any_of(sys.states.begin(), sys.states.end(),
                         [&](const auto& st) { return st.name == name; }))
          loader.fail_key(*key, prefix + "reset." + name,
                          "a state of [states] (" + join(c.state_names()) + ")",
                          "'" + name + "', not a state");
        by_state[name] = node;
      }
      for (std::size_t i = 0; i < sys.states.size(); ++i) {
        const auto it = by_state.find(sys.states[i].name);
        if (it == by_state.end()) continue;
        const std::string full = prefix + "reset." + sys.states[i].name;
        Expression tree = loader.expression(*it->second, full);
        check_names(tree, *it->second, full);
        impact.reset.emplace_back(static_cast<int>(i), std::move(tree));
      }
      sys.impacts.push_back(std::move(impact));
    }
  }

  // The forcing's period, for equations that use t: what orbits of a forced system have.
  if (const auto* n = root.get("forcing_period")) {
    if (!c.plugin_.empty())
      in.fail(*n, "forcing_period",
              "no forcing_period in a case file with a plug-in (its class declares it: "
              "OdeSystem::forcing_period)");
    if (!sys.uses_time)
      in.fail(*n, "forcing_period",
              "no forcing_period for equations that do not use t (an autonomous system's period "
              "is found, not declared)");
    sys.forcing_period = parameters_only(*n, "forcing_period",
                                         "the forcing's period does not change along the motion");
  }

  // Parameter sets and starts, as in metronome case files.
  const auto parameter_names = c.parameter_names();
  if (const auto* n = root.get("params")) {
    for (auto&& [set_name, set_node] : in.table(*n, "params")) {
      const std::string prefix = "params." + std::string(set_name.str()) + ".";
      const auto& t = in.table(set_node, prefix.substr(0, prefix.size() - 1));
      ParameterSet ps;
      ps.name = std::string(set_name.str());
      ps.line = static_cast<int>(set_node.source().begin.line);
      for (auto&& [key, node] : t) {
        const std::string k(key.str());
        if (std::find(parameter_names.begin(), parameter_names.end(), k) == parameter_names.end())
          in.fail(static_cast<int>(key.source().begin.line), prefix + k,
                  "a parameter of [parameters] (" + join(parameter_names) + ")");
        ps.entries.push_back(
            {k, in.number(node, prefix + k), static_cast<int>(node.source().begin.line)});
      }
      c.parameter_sets_.push_back(std::move(ps));
    }
  }
  if (const auto* n = root.get("default_params")) {
    c.default_params_ = in.string(*n, "default_params");
    const auto sets = c.parameter_set_names();
    if (std::find(sets.begin(), sets.end(), c.default_params_) == sets.end())
      in.fail(*n, "default_params", "the name of a [params.NAME] table (" + join(sets) + ")");
  }
  const auto states = c.state_names();
  if (const auto* n = root.get("starts")) {
    for (auto&& [start_name, start_node] : in.table(*n, "starts")) {
      const std::string prefix = "starts." + std::string(start_name.str()) + ".";
      const auto& t = in.table(start_node, prefix.substr(0, prefix.size() - 1));
      in.only(t, prefix, states);
      StartSpec s;
      s.name = std::string(start_name.str());
      s.source = in.where(start_node);
      for (auto&& [key, node] : t)
        s.values.emplace_back(std::string(key.str()),
                              in.number(node, prefix + std::string(key.str())));
      c.starts_.push_back(std::move(s));
    }
  }
  std::stable_sort(c.parameter_sets_.begin(), c.parameter_sets_.end(),
                   [](const auto& a, const auto& b) { return a.line < b.line; });
  auto line_of = [](const std::string& where) {
    return std::stoi(where.substr(where.rfind(':') + 1));
  };
  std::stable_sort(c.starts_.begin(), c.starts_.end(), [&](const auto& a, const auto& b) {
    return line_of(a.source) < line_of(b.source);
  });
  // Every parameter set must respect the bounds too, used or not.
  for (const auto& set : c.parameter_sets_) c.parameter_values(set.name);
  return c;
}

std::vector<std::string> EquationCase::parameter_set_names() const {
  std::vector<std::string> names;
  for (const auto& s : parameter_sets_) names.push_back(s.name);
  return names;
}

std::vector<std::string> EquationCase::start_names() const {
  std::vector<std::string> names;
  for (const auto& s : starts_) names.push_back(s.name);
  return names;
}

std::vector<std::string> EquationCase::state_names() const {
  std::vector<std::string> names;
  for (const auto& s : system_.states) names.push_back(s.name);
  return names;
}

std::vector<std::string> EquationCase::parameter_names() const {
  std::vector<std::string> names;
  for (const auto& p : system_.parameters) names.push_back(p.name);
  return names;
}

Eigen::VectorXd EquationCase::parameter_values(const std::string& params,
                                               const std::vector<Assignment>& sets) const {
  const auto& parameters = system_.parameters;
  Eigen::VectorXd values(static_cast<Eigen::Index>(parameters.size()));
  std::vector<std::string> sources;
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    values[static_cast<Eigen::Index>(i)] = parameters[i].value;
    sources.push_back(parameters[i].source);
  }
  const auto names = parameter_names();
  auto index = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const std::string chosen = params.empty() ? default_params_ : params;
  if (!chosen.empty()) {
    const auto it = std::find_if(parameter_sets_.begin(), parameter_sets_.end(),
                                 [&](const auto& s) { return s.name == chosen; });
    if (it == parameter_sets_.end())
      throw InputError("--params " + chosen + ": no parameter set '" + chosen + "' in " + path_ +
                       "; expected one of: " + join(parameter_set_names()));
    for (const auto& e : it->entries) {
      values[static_cast<Eigen::Index>(index(e.key))] = e.value;
      sources[index(e.key)] =
          path_ + ":" + std::to_string(e.line) + ": key 'params." + chosen + "." + e.key + "'";
    }
  }
  for (const auto& a : sets) {
    if (index(a.key) == names.size())
      throw InputError(a.source + ": unknown parameter '" + a.key +
                       "'; expected one of: " + join(names));
    values[static_cast<Eigen::Index>(index(a.key))] = a.value;
    sources[index(a.key)] = a.source;
  }
  for (std::size_t i = 0; i < parameters.size(); ++i) {
    const auto& p = parameters[i];
    const double v = values[static_cast<Eigen::Index>(i)];
    if ((p.min && v < *p.min) || (p.max && v > *p.max))
      throw InputError(sources[i] + ": expected a value of " + p.name + " within [" +
                       (p.min ? format_number(*p.min) : "-inf") + ", " +
                       (p.max ? format_number(*p.max) : "inf") + "] (" + p.source + "), got " +
                       format_number(v));
  }
  return values;
}

const StartSpec& EquationCase::start(const std::string& name) const {
  for (const auto& s : starts_)
    if (s.name == name) return s;
  if (starts_.empty())
    throw InputError("--start " + name + ": " + path_ +
                     " names no starts (no [starts.NAME] tables): its [states] are the start; "
                     "expected no --start");
  throw InputError("--start " + name + ": no start '" + name + "' in " + path_ +
                   "; expected one of: " + join(start_names()));
}

Eigen::VectorXd EquationCase::initial_state(const StartSpec* start,
                                            const std::vector<Assignment>& initial) const {
  const auto names = state_names();
  Eigen::VectorXd z(static_cast<Eigen::Index>(names.size()));
  for (std::size_t i = 0; i < names.size(); ++i)
    z[static_cast<Eigen::Index>(i)] = system_.states[i].initial;
  auto index_of = [&](const std::string& name, const std::string& source) {
    const auto it = std::find(names.begin(), names.end(), name);
    if (it == names.end())
      throw InputError(source + ": unknown state '" + name + "'; expected one of: " + join(names));
    return static_cast<Eigen::Index>(it - names.begin());
  };
  if (start)
    for (const auto& [name, value] : start->values) z[index_of(name, start->source)] = value;
  for (const auto& a : initial) z[index_of(a.key, a.source)] = a.value;
  return z;
}

}  // namespace sympathy
