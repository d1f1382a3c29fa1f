#include "cases/cli/event_name.hpp"

#include "sympathy/core/errors.hpp"

namespace sympathy::cli {

EventName parse_event_name(const std::string& text, const std::string& option) {
  EventName name;
  name.text = text;
  const std::string kind = text.substr(0, 2);
  const std::string number = text.size() > 2 ? text.substr(2) : "";
  const bool digits = !number.empty() && number.size() < 9 &&
                      number.find_first_not_of("0123456789") == std::string::npos;
  if (kind != "BP" && kind != "PD")
    throw InputError(option + " " + text +
                     ": expected a branch point or period doubling, BP or PD followed by its "
                     "number along the branch (e.g. BP1): only there is a branch born");
  if (!digits || std::stoi(number) < 1)
    throw InputError(option + " " + text + ": expected " + kind +
                     " followed by a positive number (e.g. " + kind + "1)");
  name.type = kind == "BP" ? BifurcationType::BranchPoint : BifurcationType::PeriodDoubling;
  name.ordinal = std::stoi(number);
  return name;
}

}  // namespace sympathy::cli
