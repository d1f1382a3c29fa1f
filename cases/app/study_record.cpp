#include "cases/app/study_record.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "sympathy/cases/sha256.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

namespace {

std::string file_hash(const std::string& what, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(what + " " + path + ": cannot be read");
  std::ostringstream s;
  s << in.rdbuf();
  return sha256_hex(s.str());
}

// One record line's value: no line break can enter it (values are as typed on a command line).
std::string one_line(std::string value) {
  std::replace(value.begin(), value.end(), '\n', ' ');
  return value;
}

}  // namespace

std::string StudyRecord::text() const {
  std::string text = "# sympathy study record: what a resumed run must equal\n";
  for (const auto& [what, value] : entries) text += what + " = " + one_line(value) + "\n";
  return text;
}

StudyRecord study_record(const Arguments& args,
                         const std::vector<std::pair<std::string, std::string>>& inputs,
                         const std::set<std::string>& ignored) {
  StudyRecord r;
  r.entries.emplace_back("sympathy", SYMPATHY_VERSION);
  std::map<std::string, std::vector<std::string>> options;
  for (const auto& g : args.given())
    if (!ignored.count(g.name)) options[g.name].push_back(g.text);
  for (const auto& [name, values] : options)
    for (const auto& value : values) r.entries.emplace_back("option " + name, value);
  for (const auto& [what, path] : inputs)
    if (!path.empty()) r.entries.emplace_back("file " + what, file_hash(what, path));
  return r;
}

void check_or_write_study_record(const std::string& journal_path, const StudyRecord& record,
                                 bool resuming) {
  const std::string path = journal_path + ".study";
  if (!resuming) {
    write_file_atomically(path, record.text());
    return;
  }
  std::ifstream in(path);
  if (!in)
    throw InputError(journal_path + ": no record of the study it belongs to (" + path +
                     " is missing: a journal of an earlier sympathy, or the record was removed); "
                     "expected a journal started by this version, or another --out to start anew");
  std::vector<std::pair<std::string, std::string>> recorded;
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty() || line[0] == '#') continue;
    const auto eq = line.find(" = ");
    if (eq == std::string::npos)
      throw InputError(path + ":" + std::to_string(number) +
                       ": expected WHAT = VALUE (a study record written by sympathy)");
    recorded.emplace_back(line.substr(0, eq), line.substr(eq + 3));
  }
  const auto describe = [](const std::vector<std::pair<std::string, std::string>>& entries,
                           const std::string& what) {
    std::string values;
    for (const auto& [w, v] : entries)
      if (w == what) values += (values.empty() ? "" : ", ") + v;
    return values.empty() ? std::string("not given") : values;
  };
  std::vector<std::pair<std::string, std::string>> now = record.entries;
  for (auto& e : now) e.second = one_line(e.second);
  if (recorded == now) return;
  // Every entry (in either) whose values differ, each named once.
  std::vector<std::string> names, differences;
  for (const auto& e : recorded) names.push_back(e.first);
  for (const auto& e : now) names.push_back(e.first);
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto& what = names[i];
    if (std::find(names.begin(), names.begin() + static_cast<std::ptrdiff_t>(i), what) !=
        names.begin() + static_cast<std::ptrdiff_t>(i))
      continue;
    const auto then = describe(recorded, what), today = describe(now, what);
    if (then == today) continue;
    const bool file = what.rfind("file ", 0) == 0;
    differences.push_back(what +
                          (file ? " has changed since the journal was started (its SHA-256 " +
                                      then + ", now " + today + ")"
                                : " was " + then + " when the journal was started, now " + today));
  }
  if (differences.empty()) return;  // the same entries in another order
  std::string list;
  for (const auto& d : differences) list += (list.empty() ? "" : "; ") + d;
  throw InputError(journal_path + ": a journal of another study: " + list +
                   "; expected --resume with the same study, or another --out to start anew");
}

}  // namespace sympathy::app
