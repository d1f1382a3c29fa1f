// Names of a branch's events on the command line and in study files: "BP1", "PD2" (the type,
// then its 1-based number among the branch's events of that type). Its own file: the study
// file reader (and its fuzz target) checks them without the branch machinery.
#pragma once

#include <string>
#include <vector>

#include "sympathy/continuation/branch.hpp"

namespace sympathy::app {

// The event a name like "BP1" (type, then its 1-based number among the branch's events of that
// type) picks. parse_event_name checks the name before any work: InputError naming `option`
// unless its type is one of `allowed` (by default BP and PD, the events a branch can be switched
// at; `expected` says what is) and its number a positive one.
struct EventName {
  BifurcationType type = BifurcationType::BranchPoint;
  int ordinal = 1;
  std::string text;
};
EventName parse_event_name(const std::string& text, const std::string& option,
                           const std::vector<BifurcationType>& allowed =
                               {BifurcationType::BranchPoint, BifurcationType::PeriodDoubling},
                           const std::string& expected =
                               "a branch point or period doubling, BP or PD followed by its "
                               "number along the branch (e.g. BP1): only there is a branch "
                               "born");

}  // namespace sympathy::app
