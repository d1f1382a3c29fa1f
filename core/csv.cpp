#include "core/csv.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>

#include "core/errors.hpp"

namespace sympathy {

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, end);
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& header)
    : path_(path), columns_(header.size()) {
  file_ = std::fopen(path.c_str(), "w");
  if (!file_) throw InputError(path + ": cannot open for writing");
  row(header);
}

CsvWriter::~CsvWriter() {
  if (file_) std::fclose(file_);
}

void CsvWriter::row(const std::vector<std::string>& fields) {
  if (fields.size() != columns_) throw std::logic_error("CSV row of the wrong width");
  std::string line;
  for (std::size_t i = 0; i < fields.size(); ++i) {
    if (i) line += ',';
    // RFC 4180: a field with a comma, quote or line break is quoted, its quotes doubled.
    if (fields[i].find_first_of(",\"\n\r") == std::string::npos) {
      line += fields[i];
    } else {
      line += '"';
      for (char c : fields[i]) line += c == '"' ? std::string("\"\"") : std::string(1, c);
      line += '"';
    }
  }
  line += '\n';
  std::fputs(line.c_str(), file_);
}

void CsvWriter::row(const std::vector<double>& values) {
  std::vector<std::string> fields;
  fields.reserve(values.size());
  for (double v : values) fields.push_back(format_double(v));
  row(fields);
}

void CsvWriter::flush() {
  std::fflush(file_);
}

}  // namespace sympathy
