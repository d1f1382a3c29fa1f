// Names of a branch's events on the command line and in study files: "BP1", "PD2" (the type,
// then its 1-based number among the branch's events of that type). Its own file: the study
// file reader (and its fuzz target) checks them without the branch machinery.
#pragma once

#include <string>

#include "sympathy/continuation/branch.hpp"

namespace sympathy::cli {

// The event a name like "BP1" (type, then its 1-based number among the branch's events of that
// type) picks. parse_event_name checks the name before any work: InputError naming `option`
// unless it is BP or PD (the events a branch can be switched at) and a positive number.
struct EventName {
  BifurcationType type = BifurcationType::BranchPoint;
  int ordinal = 1;
  std::string text;
};
EventName parse_event_name(const std::string& text, const std::string& option);

}  // namespace sympathy::cli
