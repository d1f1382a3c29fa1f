#include "sympathy/core/recording.hpp"

#include <algorithm>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

Recording read_recording(const std::string& path, const std::vector<std::string>& state_names,
                         const std::string& system) {
  const CsvTable table = read_csv(path);
  const std::string known = join(state_names);
  if (table.header[0] != "t")
    throw InputError(path + ":1: column 1 is '" + table.header[0] +
                     "'; expected 't' (time in s) first, then state columns of " + system + " (" +
                     known + ")");
  Recording r;
  r.path = path;
  for (std::size_t j = 1; j < table.header.size(); ++j) {
    const auto& name = table.header[j];
    const auto it = std::find(state_names.begin(), state_names.end(), name);
    if (it == state_names.end())
      throw InputError(path + ":1: column " + std::to_string(j + 1) + " '" + name +
                       "' is not a state of " + system + "; expected t, then any of: " + known);
    r.columns.push_back(name);
    r.components.push_back(static_cast<int>(it - state_names.begin()));
  }
  if (r.columns.empty())
    throw InputError(path + ":1: only a time column; expected t, then one or more of: " + known);

  const int n = static_cast<int>(table.rows.size());
  const int m = static_cast<int>(r.columns.size());
  r.values.resize(n, m);
  r.times.resize(n);
  r.lines = table.lines;
  for (int i = 0; i < n; ++i) {
    const auto& row = table.rows[i];
    r.times[i] = row[0];
    if (i > 0 && !(row[0] > r.times[i - 1]))
      throw InputError(path + ":" + std::to_string(table.lines[i]) + ": column 't': time " +
                       format_double(row[0]) + " after " + format_double(r.times[i - 1]) +
                       " (line " + std::to_string(table.lines[i - 1]) +
                       "); expected strictly increasing times");
    for (int k = 0; k < m; ++k) r.values(i, k) = row[k + 1];
  }
  return r;
}

}  // namespace sympathy
