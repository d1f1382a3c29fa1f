#include "sympathy/continuation/task_journal.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::istringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

std::string line_of(std::size_t task, const std::vector<std::string>& fields) {
  std::string line = std::to_string(task);
  for (const auto& f : fields) line += "," + f;
  return line + "\n";
}

}  // namespace

StreamFile::Mode TaskJournal::read_existing(const std::string& path, const Row& header,
                                            std::size_t task_count, bool resume,
                                            std::map<std::size_t, Row>& rows) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (!resume || !fs::exists(path, ec)) return StreamFile::Mode::Truncate;
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot read the journal to resume it");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // A last line without its line end was cut short: drop it from the file before appending.
  const std::size_t end = text.rfind('\n');
  const std::size_t whole = end == std::string::npos ? 0 : end + 1;
  if (whole < text.size()) {
    fs::resize_file(path, whole, ec);
    if (ec)
      throw OutputError(path + ": cannot drop the journal's cut-off last line (" + ec.message() +
                        ")");
    text.resize(whole);
  }
  const std::string expected = "task," + join(header, ",");
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const std::string where = path + ":" + std::to_string(number) + ": ";
    if (number == 1) {
      if (line != expected)
        throw InputError(where + "the journal's header is '" + line + "'; expected '" + expected +
                         "' (a journal of another kind of run)");
      continue;
    }
    auto fields = split(line);
    if (fields.size() != header.size() + 1)
      throw InputError(where + "a row of " + std::to_string(fields.size()) + " fields; expected " +
                       std::to_string(header.size() + 1));
    std::size_t task = 0, used = 0;
    try {
      task = std::stoul(fields[0], &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != fields[0].size() || fields[0][0] == '-' || task >= task_count)
      throw InputError(where + "task '" + fields[0] + "'; expected a task index below " +
                       std::to_string(task_count) + " (a journal of another run?)");
    fields.erase(fields.begin());
    if (!rows.emplace(task, std::move(fields)).second)
      throw InputError(where + "task " + std::to_string(task) + " a second time");
  }
  if (number == 0) return StreamFile::Mode::Truncate;  // empty: begin it again
  return StreamFile::Mode::Append;
}

TaskJournal::TaskJournal(const std::string& path, Row header, std::size_t task_count, bool resume)
    : header_(std::move(header)),
      task_count_(task_count),
      mode_(read_existing(path, header_, task_count, resume, rows_)),
      file_(path, mode_) {
  resumed_ = rows_.size();
  if (mode_ == StreamFile::Mode::Truncate) file_.write_line("task," + join(header_, ",") + "\n");
}

void TaskJournal::append(std::size_t task, Row fields) {
  if (task >= task_count_) throw std::invalid_argument("TaskJournal: task index out of range");
  if (fields.size() != header_.size())
    throw std::invalid_argument("TaskJournal: a row of " + std::to_string(fields.size()) +
                                " fields for " + std::to_string(header_.size()) + " columns");
  for (const auto& f : fields)
    if (f.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("TaskJournal: field '" + f + "' has a comma, quote or line end");
  if (rows_.count(task)) throw std::invalid_argument("TaskJournal: task recorded twice");
  file_.write_line(line_of(task, fields));
  rows_.emplace(task, std::move(fields));
}

std::vector<bool> TaskJournal::done() const {
  std::vector<bool> done(task_count_, false);
  for (const auto& [task, row] : rows_) done[task] = true;
  return done;
}

std::string TaskJournal::table() const {
  std::string text = "task," + join(header_, ",") + "\n";
  for (const auto& [task, row] : rows_) text += line_of(task, row);
  return text;
}

}  // namespace sympathy
