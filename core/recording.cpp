#include "sympathy/core/recording.hpp"

#include <algorithm>
#include <cmath>

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
    for (int k = 0; k < m; ++k) {
      // A value whose square overflows makes every residual sum infinite or NaN (issue 32: a
      // sample of 1e300 gave "RSS 0 -> 0", "RMS -nan" and "converged"): refused, named.
      if (std::abs(row[k + 1]) > kMaxRecordedMagnitude)
        throw InputError(path + ":" + std::to_string(table.lines[i]) + ": column '" + r.columns[k] +
                         "': " + format_double(row[k + 1]) +
                         "; expected a value of magnitude at most 1e150 (its square must not "
                         "overflow in a least-squares fit)");
      r.values(i, k) = row[k + 1];
    }
  }
  return r;
}

}  // namespace sympathy
