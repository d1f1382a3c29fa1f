// CSV files. Writing: row by row, each row written whole and flushed (StreamFile), so a run that
// stops early keeps everything computed before it stopped, and a failed write is an OutputError.
// Reading: a header line of column names, then rows of numbers, every mistake reported with the
// file, line and column.
#pragma once

#include <string>
#include <vector>

#include "sympathy/core/output_file.hpp"

namespace sympathy {

class CsvWriter {
 public:
  // Opens (truncates) `path` and writes the header; throws OutputError if it cannot.
  CsvWriter(const std::string& path, const std::vector<std::string>& header);

  // One row of numbers, shortest round-trip representation.
  void row(const std::vector<double>& values);
  // One row of preformatted fields.
  void row(const std::vector<std::string>& fields);
  // Closes the file, checked (OutputError).
  void close() { file_.close(); }
  const std::string& path() const { return file_.path(); }

 private:
  StreamFile file_;
  std::size_t columns_ = 0;
};

// Shortest representation that reads back to the same double.
std::string format_double(double v);

// A CSV table of numbers: the header's names and the rows, each with its line in the file.
struct CsvTable {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  std::vector<int> lines;  // 1-based line of each row in the file
};

// Reads `path`: a header line naming the columns (distinct, not empty), then one line of finite
// numbers per row, separated by commas (spaces around fields and CRLF line ends are accepted;
// blank lines at the end of the file are ignored). Throws InputError naming the file, the line,
// the column and what was expected: a missing file, an empty file, an unnamed or repeated column,
// an empty row, a row of the wrong width, an empty field, a field that is not a finite number, no
// rows at all.
CsvTable read_csv(const std::string& path);

}  // namespace sympathy
