#include "sympathy/core/csv.hpp"

#include "sympathy/core/text.hpp"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "sympathy/core/errors.hpp"

namespace sympathy {

std::string format_double(double v) {
  if (std::isnan(v)) return "nan";
  char buffer[32];
  auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, end);
}

CsvWriter::CsvWriter(const std::string& path, const std::vector<std::string>& header)
    : file_(path), columns_(header.size()) {
  row(header);
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
  file_.write_line(line);
}

void CsvWriter::row(const std::vector<double>& values) {
  std::vector<std::string> fields;
  fields.reserve(values.size());
  for (double v : values) fields.push_back(format_double(v));
  row(fields);
}

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return "";
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields;
  std::size_t begin = 0;
  while (true) {
    const auto comma = line.find(',', begin);
    fields.push_back(
        trim(line.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin)));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return fields;
}

}  // namespace

CsvTable read_csv(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw InputError(path + ": cannot read the file (a directory; expected a CSV file)");
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the file (no such file, or not readable)");
  CsvTable table;
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  while (!lines.empty() && trim(lines.back()).empty()) lines.pop_back();  // blank lines at the end
  if (lines.empty())
    throw InputError(path + ": the file is empty; expected a header line naming the columns");

  table.header = split_fields(lines[0]);
  for (std::size_t j = 0; j < table.header.size(); ++j) {
    const std::string where = path + ":1: column " + std::to_string(j + 1);
    if (table.header[j].empty()) throw InputError(where + " has no name; expected a column name");
    for (std::size_t i = 0; i < j; ++i)
      if (table.header[i] == table.header[j])
        throw InputError(where + ": '" + table.header[j] + "' repeats column " +
                         std::to_string(i + 1) + "; expected distinct column names");
  }
  const std::size_t width = table.header.size();
  const std::string expected =
      std::string("expected ") + std::to_string(width) + " fields (" + join(table.header) + ")";
  for (std::size_t l = 1; l < lines.size(); ++l) {
    const int line_number = static_cast<int>(l) + 1;
    const std::string where = path + ":" + std::to_string(line_number);
    if (trim(lines[l]).empty()) throw InputError(where + ": empty row; " + expected);
    const auto fields = split_fields(lines[l]);
    if (fields.size() != width)
      throw InputError(where + ": " + expected + ", got " + std::to_string(fields.size()));
    std::vector<double> row(width);
    for (std::size_t j = 0; j < width; ++j) {
      const std::string column =
          where + ": column '" + table.header[j] + "' (field " + std::to_string(j + 1) + ")";
      const std::string& f = fields[j];
      if (f.empty()) throw InputError(column + ": empty field; expected a number");
      double v = 0.0;
      const char* first = f.data();
      const char* last = f.data() + f.size();
      // from_chars takes no '+'; skip one, but not before a sign ("+-1" is no number).
      if (*first == '+' && f.size() > 1 && first[1] != '-' && first[1] != '+') ++first;
      auto [end, ec] = std::from_chars(first, last, v);
      if (ec != std::errc() || end != last)
        throw InputError(column + ": expected a number, got '" + f + "'");
      if (!std::isfinite(v))
        throw InputError(column + ": expected a finite number, got '" + f + "'");
      row[j] = v;
    }
    table.rows.push_back(std::move(row));
    table.lines.push_back(line_number);
  }
  if (table.rows.empty())
    throw InputError(path + ": no rows after the header; expected one row of numbers per sample");
  return table;
}

}  // namespace sympathy
