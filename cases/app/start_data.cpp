#include "cases/app/start_data.hpp"

#include <cmath>
#include <cstdio>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::app {

std::optional<std::string> start_data_path(const Arguments& args) {
  const auto path = args.value("--start-data");
  if (!path) return std::nullopt;
  for (const char* other : {"--start", "--initial", "--transient"})
    if (args.has(other))
      throw InputError(std::string(other) + ": not with --start-data " + *path +
                       " (the recording's first row is the start, and Newton starts there "
                       "without a transient); expected one or the other");
  return *path;
}

std::optional<double> period_guess(const Arguments& args) {
  if (!args.has("--period-guess")) return std::nullopt;
  const double T = args.number("--period-guess", 0.0);
  for (const char* other : {"--start-data", "--from-point", "--transient"})
    if (args.has(other))
      throw InputError("--period-guess " + format_number(T) + ": not with " + other +
                       " (Newton starts at once from the start state with this period)");
  if (!(T > 0.0 && std::isfinite(T)))
    throw InputError("--period-guess " + format_number(T) + ": expected a positive period");
  return T;
}

std::optional<double> data_period(const Arguments& args) {
  if (!args.has("--data-period")) return std::nullopt;
  const double T = args.number("--data-period", 0.0);
  if (!args.has("--start-data"))
    throw InputError("--data-period " + format_number(T) +
                     ": expected --start-data FILE too (the recording whose time it scales)");
  if (!(T > 0.0 && std::isfinite(T)))
    throw InputError("--data-period " + format_number(T) + ": expected a positive period");
  return T;
}

void scale_time(RecordedPeriod& r, double period) {
  r.start_time *= period;
  r.span *= period;
  r.period *= period;
  r.scaled_by = period;
}

std::optional<RecordedPeriod> start_data(const Arguments& args,
                                         const std::vector<std::string>& state_names,
                                         const std::string& system,
                                         const std::vector<int>& angles) {
  const auto path = start_data_path(args);
  if (!path) return std::nullopt;
  return read_recorded_period(*path, state_names, system, angles);
}

std::string describe_start_data(const RecordedPeriod& r) {
  char text[160];
  std::snprintf(text, sizeof text, " (%d rows over %.6g s; period guess %.9g s: %s", r.rows, r.span,
                r.period, r.returned ? "its first return, line " : "its time span");
  std::string s = "data " + r.path + text;
  if (r.returned) s += std::to_string(r.return_line);
  if (r.scaled_by > 0.0) s += ", its time scaled by --data-period " + format_double(r.scaled_by);
  return s + ")";
}

}  // namespace sympathy::app
