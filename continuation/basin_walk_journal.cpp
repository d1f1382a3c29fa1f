#include "sympathy/continuation/basin_walk_journal.hpp"

#include <cctype>
#include <cstdio>
#include <sstream>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

std::string exact(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

std::string numbers(const Eigen::VectorXd& v) {
  std::string s;
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (i > 0) s += ' ';
    s += exact(v[i]);
  }
  return s;
}

double number(const std::string& text, const std::string& where, const char* column) {
  const auto x = whole_number(text);
  if (!x)
    throw InputError(where + ": column '" + column + "': expected a number, got '" + text + "'");
  return *x;
}

Eigen::VectorXd vector_of(const std::string& text, const std::string& where) {
  std::istringstream in(text);
  std::vector<double> values;
  std::string word;
  while (in >> word) values.push_back(number(word, where, "state"));
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size()));
}

constexpr Fate kFates[] = {Fate::Certified, Fate::Reached,    Fate::NewOrbit, Fate::Equilibrium,
                           Fate::Torus,     Fate::Unresolved, Fate::Failed};

}  // namespace

TaskJournal::Row walk_journal_header() {
  return {"value",           "start",  "fate",  "attractor", "stopped_at",
          "rotation_number", "period", "state", "note"};
}

TaskJournal::Row walk_journal_row(double value, std::size_t start, const AttractorFate& fate) {
  std::string note;
  for (const char ch : fate.note) {
    if (ch == ',' || ch == '"' || ch == '\n' || ch == '\r' || ch == '%' || ch == '\x1e' ||
        ch == '\x1f') {
      char code[4];
      std::snprintf(code, sizeof code, "%%%02X", static_cast<unsigned char>(ch));
      note += code;
    } else {
      note += ch;
    }
  }
  const bool orbit = fate.fate == Fate::NewOrbit && fate.orbit;
  return {exact(value),
          std::to_string(start),
          to_string(fate.fate),
          std::to_string(fate.attractor),
          exact(fate.stopped_at),
          fate.fate == Fate::Torus ? exact(fate.rotation_number) : "",
          orbit ? exact(fate.orbit->period) : "",
          orbit                            ? numbers(fate.orbit->state0)
          : fate.fate == Fate::Equilibrium ? numbers(fate.equilibrium_state)
                                           : "",
          note};
}

AttractorFate walk_journal_fate(const TaskJournal::Row& row, const std::string& where) {
  if (row.size() != walk_journal_header().size())
    throw InputError(where + ": expected " + std::to_string(walk_journal_header().size()) +
                     " fields after the task, got " + std::to_string(row.size()));
  AttractorFate fate;
  bool known = false;
  for (const Fate f : kFates)
    if (row[2] == to_string(f)) {
      fate.fate = f;
      known = true;
    }
  if (!known) throw InputError(where + ": column 'fate': not a fate, '" + row[2] + "'");
  fate.attractor = static_cast<int>(number(row[3], where, "attractor"));
  fate.stopped_at = number(row[4], where, "stopped_at");
  if (fate.fate == Fate::Torus) fate.rotation_number = number(row[5], where, "rotation_number");
  if (fate.fate == Fate::NewOrbit && !row[6].empty()) {
    fate.orbit.emplace();
    fate.orbit->period = number(row[6], where, "period");
    fate.orbit->state0 = vector_of(row[7], where);
  }
  if (fate.fate == Fate::Equilibrium) fate.equilibrium_state = vector_of(row[7], where);
  const std::string& note = row[8];
  for (std::size_t i = 0; i < note.size(); ++i) {
    if (note[i] == '%' && i + 2 < note.size() &&
        std::isxdigit(static_cast<unsigned char>(note[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(note[i + 2]))) {
      fate.note += static_cast<char>(std::stoi(note.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      fate.note += note[i];
    }
  }
  return fate;
}

}  // namespace sympathy
