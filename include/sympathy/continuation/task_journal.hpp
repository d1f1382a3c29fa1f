// The journal of a run of numbered tasks (task_runner.hpp): one CSV row per finished task,
// streamed as the task finishes (each row whole and flushed, through StreamFile), so that a run
// that is killed keeps every finished task, and a run started again with the journal (resume)
// computes only the tasks that are not in it.
//
// The first column is the task's index; the others are the caller's, plain fields (no comma,
// quote or line break: numbers and names). Rows are in the order tasks finished, which depends on
// the threads; table() gives them in task order, which does not: the final files are written from
// it, so a resumed run's files equal an uninterrupted run's.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "sympathy/core/output_file.hpp"

namespace sympathy {

class TaskJournal {
 public:
  using Row = std::vector<std::string>;  // the fields after the task index

  // Without `resume`, or when `path` does not exist: creates `path` (truncating it) and writes
  // the header "task,<header>". With `resume` and an existing file: reads it, then appends to it.
  // A last line without its line end (the write a kill cut short) is dropped from the file. Throws
  // InputError naming the file and line when it is not a journal of this run: another header, a
  // row of another width, a task index that is not an integer below `task_count`, a task twice.
  // Throws OutputError when the file cannot be written.
  TaskJournal(const std::string& path, Row header, std::size_t task_count, bool resume);

  // Writes the row of `task` (whole, flushed) and keeps it. Throws std::invalid_argument for a
  // task already in the journal, a row of the wrong width or a field with a comma, quote or line
  // break; OutputError when the write fails.
  void append(std::size_t task, Row fields);
  void close() { file_.close(); }

  const std::string& path() const { return file_.path(); }
  const Row& header() const { return header_; }
  // Every row so far (read and appended), by task.
  const std::map<std::size_t, Row>& rows() const { return rows_; }
  // Per task: whether it is in the journal (for run_tasks).
  std::vector<bool> done() const;
  // Rows that were in the file when it was opened (0 for a new journal).
  std::size_t resumed() const { return resumed_; }
  // The journal as a CSV table in task order: the header line, then one line per task in it.
  std::string table() const;

 private:
  static StreamFile::Mode read_existing(const std::string& path, const Row& header,
                                        std::size_t task_count, bool resume,
                                        std::map<std::size_t, Row>& rows);

  Row header_;
  std::size_t task_count_;
  std::map<std::size_t, Row> rows_;
  std::size_t resumed_ = 0;
  StreamFile::Mode mode_;  // Append when resuming a journal with its header
  StreamFile file_;
};

}  // namespace sympathy
