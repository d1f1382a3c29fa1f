// --start-data FILE.csv (orbit, continue): an orbit started from one recorded or simulated period
// instead of a named start and a transient (continuation/recorded_period.hpp), for metronome and
// equation case files alike. The file is read and checked as the arguments are, before any work.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "cases/app/arguments.hpp"
#include "sympathy/continuation/recorded_period.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy::app {

// The recorded period --start-data names (nullopt without it), checked against the system's
// state names; InputError for --start, --initial or --transient beside it (the recording's first
// row is the start, and nothing is integrated before Newton).
// The path --start-data names (nullopt without it), with the same check of the options beside it.
std::optional<std::string> start_data_path(const Arguments& args);
std::optional<RecordedPeriod> start_data(const Arguments& args,
                                         const std::vector<std::string>& state_names,
                                         const std::string& system,
                                         const std::vector<int>& angles = {});

// --period-guess (nullopt without it); InputError beside a start that carries its own period
// (--start-data, --from-point) or a transient (--transient), and for a period that is not positive.
std::optional<double> period_guess(const Arguments& args);

// --data-period (nullopt without it): the period of a recording whose time is scaled to [0, 1]
// (AUTO's dat files); InputError without --start-data or for a period that is not positive.
std::optional<double> data_period(const Arguments& args);
// The recording's times (start, span, period guess) multiplied by `period`.
void scale_time(RecordedPeriod& r, double period);

// "data FILE.csv (N rows over S s; period guess T s: the first return, line L)" for the reports.
std::string describe_start_data(const RecordedPeriod& recorded);

}  // namespace sympathy::app
