// A CSV file written row by row and flushed as it goes, so a run that stops early keeps
// everything computed before it stopped.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

namespace sympathy {

class CsvWriter {
 public:
  // Opens (truncates) `path` and writes the header; throws InputError if it cannot.
  CsvWriter(const std::string& path, const std::vector<std::string>& header);
  ~CsvWriter();
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  // One row of numbers, shortest round-trip representation.
  void row(const std::vector<double>& values);
  // One row of preformatted fields.
  void row(const std::vector<std::string>& fields);
  void flush();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::FILE* file_ = nullptr;
  std::size_t columns_ = 0;
};

// Shortest representation that reads back to the same double.
std::string format_double(double v);

}  // namespace sympathy
