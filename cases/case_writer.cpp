#include "sympathy/cases/case_writer.hpp"
#include "sympathy/cases/names.hpp"
#include "sympathy/core/output_file.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "sympathy/core/csv.hpp"

namespace sympathy {

namespace {

// Byte offset of a 1-based column counted in UTF-8 code points (toml++'s columns).
std::size_t byte_offset(const std::string& line, int column) {
  std::size_t i = 0;
  for (int c = 1; c < column && i < line.size(); ++c) {
    ++i;
    while (i < line.size() && (static_cast<unsigned char>(line[i]) & 0xC0) == 0x80) ++i;
  }
  return i;
}

// Where the line's '#' comment starts, outside strings; npos if none.
std::size_t comment_start(const std::string& line, std::size_t from) {
  char quote = 0;
  for (std::size_t i = from; i < line.size(); ++i) {
    const char ch = line[i];
    if (quote) {
      if (ch == '\\' && quote == '"') {
        ++i;
      } else if (ch == quote) {
        quote = 0;
      }
    } else if (ch == '"' || ch == '\'') {
      quote = ch;
    } else if (ch == '#') {
      return i;
    }
  }
  return std::string::npos;
}

struct Replacement {
  int line = 0;                    // 1-based
  std::size_t begin = 0, end = 0;  // byte offsets in the line
  std::string text;
  std::string note;
};

class Editor {
 public:
  Editor(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw InputError(path + ": cannot read the case file");
    for (std::string line; std::getline(in, line);) lines_.push_back(line);
  }

  // Replaces the value of `node` with `text`.
  void replace(const toml::node& node, const std::string& text, const std::string& note) {
    const auto& s = node.source();
    if (s.begin.line != s.end.line)
      throw std::logic_error("case writer: a value spanning lines at " + path_ + ":" +
                             std::to_string(s.begin.line));
    const std::string& line = lines_.at(s.begin.line - 1);
    Replacement r;
    r.line = static_cast<int>(s.begin.line);
    r.begin = byte_offset(line, static_cast<int>(s.begin.column));
    r.end = byte_offset(line, static_cast<int>(s.end.column));
    r.text = text;
    r.note = note;
    replacements_.push_back(r);
  }
  std::string old_text(const toml::node& node) const {
    const auto& s = node.source();
    const std::string& line = lines_.at(s.begin.line - 1);
    const std::size_t b = byte_offset(line, static_cast<int>(s.begin.column));
    return line.substr(b, byte_offset(line, static_cast<int>(s.end.column)) - b);
  }
  // Inserts a line after line `after` (0: at the top).
  void insert_after(int after, const std::string& text) { insertions_[after].push_back(text); }
  int line_count() const { return static_cast<int>(lines_.size()); }
  const std::string& line(int number) const { return lines_.at(number - 1); }

  std::string text() const {
    std::map<int, std::vector<const Replacement*>> by_line;
    for (const auto& r : replacements_) by_line[r.line].push_back(&r);
    std::ostringstream out;
    auto emit_insertions = [&](int after) {
      auto it = insertions_.find(after);
      if (it != insertions_.end())
        for (const auto& l : it->second) out << l << "\n";
    };
    emit_insertions(0);
    for (int number = 1; number <= line_count(); ++number) {
      std::string line = lines_[number - 1];
      auto it = by_line.find(number);
      if (it != by_line.end()) {
        auto edits = it->second;
        std::sort(edits.begin(), edits.end(), [](auto a, auto b) { return a->begin > b->begin; });
        std::string notes;
        for (const auto* r : edits) {
          // Keep a comment's column where it was: take or give the spaces after the value.
          std::string tail = line.substr(r->end);
          const long grow =
              static_cast<long>(r->text.size()) - static_cast<long>(r->end - r->begin);
          std::size_t spaces = 0;
          while (spaces < tail.size() && tail[spaces] == ' ') ++spaces;
          if (spaces > 0 && spaces < tail.size() && tail[spaces] == '#') {
            if (grow > 0)
              tail.erase(0, std::min<std::size_t>(static_cast<std::size_t>(grow), spaces - 1));
            else
              tail.insert(0, static_cast<std::size_t>(-grow), ' ');
          }
          line = line.substr(0, r->begin) + r->text + tail;
          notes = notes.empty() ? r->note : r->note + "; " + notes;
        }
        const std::size_t hash = comment_start(line, 0);
        if (hash == std::string::npos) {
          line += "  # " + notes;
        } else {
          std::string old = line.substr(hash + 1);
          while (!old.empty() && old.front() == ' ') old.erase(0, 1);
          line = line.substr(0, hash) + "# " + notes + (old.empty() ? "" : " | " + old);
        }
      }
      out << line << "\n";
      emit_insertions(number);
    }
    return out.str();
  }

 private:
  std::string path_;
  std::vector<std::string> lines_;
  std::vector<Replacement> replacements_;
  std::map<int, std::vector<std::string>> insertions_;
};

// The last line a table's own entries occupy (its header line if it has none).
int last_line(const toml::table& table) {
  int last = static_cast<int>(table.source().begin.line);
  for (auto&& [key, node] : table) last = std::max(last, static_cast<int>(node.source().end.line));
  return last;
}

std::string toml_quoted(const std::string& s) {
  return "\"" + s + "\"";
}

}  // namespace

std::vector<std::string> write_case_with_values(const CaseFile& file, const std::string& params,
                                                const std::vector<NewValue>& values,
                                                const std::vector<std::string>& header,
                                                const std::string& out_path) {
  const toml::table root = read_toml(file.path(), "case file");
  Editor editor(file.path());
  for (const auto& h : header) editor.insert_after(0, h.empty() ? "#" : "# " + h);
  std::vector<std::string> edits;
  const std::string set = params.empty() ? file.default_parameter_set() : params;

  auto where = [](const toml::node& node) {
    return std::string("line ") + std::to_string(node.source().begin.line);
  };
  auto replace = [&](const toml::node& node, const std::string& key, const NewValue& v) {
    const std::string old = editor.old_text(node);
    editor.replace(node, format_double(v.value), v.note + " (was " + old + ")");
    edits.push_back(key + " (" + where(node) + "): " + old + " -> " + format_double(v.value));
  };
  std::vector<const NewValue*> unplaced;

  const toml::table* set_table = nullptr;
  if (!set.empty()) {
    set_table = root["params"][set].as_table();
    if (!set_table || set_table->is_inline())
      throw InputError(file.path() + ": [params." + set +
                       "] is not a table of its own (inline?); expected one to write into");
  }
  for (const auto& v : values) {
    // 1. The set in use gives it: replace the entry.
    if (set_table)
      if (const auto* node = set_table->get(v.name)) {
        replace(*node, "params." + set + "." + v.name, v);
        continue;
      }
    // 2. The key of the file that gives it: replace in place.
    const auto [key, index] = split_index(v.name);
    if (v.name == "kappa" || key == "kappa") {
      const auto* springs = root["springs"].as_array();
      bool placed = false;
      if (springs)
        for (std::size_t j = 0; j < springs->size(); ++j) {
          if (index != 0 && static_cast<int>(j) + 1 != index) continue;
          if (const auto* t = (*springs)[j].as_table())
            if (const auto* kappa = t->get("kappa")) {
              replace(*kappa, "springs[" + std::to_string(j + 1) + "].kappa", v);
              placed = true;
            }
        }
      if (placed) continue;
    }
    const toml::node* node = nullptr;
    std::string path;
    const toml::table* entry = nullptr;  // [[metronomes]] entry of an indexed metronome key
    if (v.name == "g") {
      node = root.get("g");
      path = "g";
    } else if (v.name == "M" || v.name == "c" || v.name == "k" || v.name == "cx" ||
               v.name == "cy" || v.name == "kx" || v.name == "ky") {
      node = root["platform"][v.name].node();
      path = "platform." + v.name;
    } else if (index == 0) {
      node = root["metronome"][v.name].node();
      path = "metronome." + v.name;
    } else if (key != "kappa") {
      const auto* list = root["metronomes"].as_array();
      if (list && index <= static_cast<int>(list->size())) entry = (*list)[index - 1].as_table();
      path = "metronomes[" + std::to_string(index) + "]." + key;
      if (entry) node = entry->get(key);
    }
    if (node) {
      replace(*node, path, v);
      continue;
    }
    // 3. Not given by a key: a new entry in the set in use ...
    if (set_table) {
      const int after = last_line(*set_table);
      editor.insert_after(after, v.name + " = " + format_double(v.value) + "  # " + v.note);
      edits.push_back("params." + set + "." + v.name + " (added after line " +
                      std::to_string(after) + "): " + format_double(v.value));
      continue;
    }
    // ... or in the metronome's own table ...
    if (entry && !entry->is_inline()) {
      const int line = static_cast<int>(entry->source().begin.line);
      editor.insert_after(line, key + " = " + format_double(v.value) + "  # " + v.note);
      edits.push_back(path + " (added after line " + std::to_string(line) +
                      "): " + format_double(v.value));
      continue;
    }
    // ... or a new set.
    unplaced.push_back(&v);
  }

  // What has no place of its own goes into a new parameter set, made the default.
  std::string new_default = set;
  if (!unplaced.empty()) {
    std::string name = "fitted";
    for (int i = 2; root["params"][name]; ++i) name = "fitted" + std::to_string(i);
    editor.insert_after(editor.line_count(), "");
    editor.insert_after(editor.line_count(), "[params." + name + "]  # written by sympathy fit");
    for (const auto* v : unplaced) {
      editor.insert_after(editor.line_count(),
                          v->name + " = " + format_double(v->value) + "  # " + v->note);
      edits.push_back("params." + name + "." + v->name + " (new set): " + format_double(v->value));
    }
    new_default = name;
  }
  if (!new_default.empty() && new_default != file.default_parameter_set()) {
    if (const auto* node = root.get("default_params")) {
      const std::string old = editor.old_text(*node);
      editor.replace(*node, toml_quoted(new_default),
                     "the parameter set the fit used (was " + old + ")");
      edits.push_back("default_params (" + where(*node) + "): " + old + " -> " +
                      toml_quoted(new_default));
    } else {
      // A top-level key goes before the first table header.
      int first_table = editor.line_count() + 1;
      for (int l = 1; l <= editor.line_count(); ++l) {
        const auto& text = editor.line(l);
        const auto first = text.find_first_not_of(" \t");
        if (first != std::string::npos && text[first] == '[') {
          first_table = l;
          break;
        }
      }
      editor.insert_after(first_table - 1, "default_params = " + toml_quoted(new_default) +
                                               "  # the parameter set written by sympathy fit");
      edits.push_back("default_params (added): " + toml_quoted(new_default));
    }
  }
  write_file_atomically(out_path, editor.text());

  // The copy must load and give the values (a set entry such as cx can hide a value of c
  // written in place: the file's own layering, which this check catches).
  const CaseFile copy = CaseFile::load(out_path);
  const ModelSpec spec = copy.spec();
  for (const auto& v : values)
    if (spec.get(v.name) != v.value)
      throw std::runtime_error(out_path + ": written, but it gives " + v.name + " = " +
                               format_double(spec.get(v.name)) + " instead of " +
                               format_double(v.value) +
                               " (another key of the file overrides it); edit it by hand");
  return edits;
}

}  // namespace sympathy
