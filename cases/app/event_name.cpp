#include "cases/app/event_name.hpp"

#include <algorithm>

#include "sympathy/core/errors.hpp"

namespace sympathy::app {

EventName parse_event_name(const std::string& text, const std::string& option,
                           const std::vector<BifurcationType>& allowed,
                           const std::string& expected) {
  EventName name;
  name.text = text;
  const std::string kind = text.substr(0, 2);
  const std::string number = text.size() > 2 ? text.substr(2) : "";
  const bool digits = !number.empty() && number.size() < 9 &&
                      number.find_first_not_of("0123456789") == std::string::npos;
  const auto type = std::find_if(allowed.begin(), allowed.end(),
                                 [&](BifurcationType t) { return to_string(t) == kind; });
  if (type == allowed.end()) throw InputError(option + " " + text + ": expected " + expected);
  if (!digits || std::stoi(number) < 1)
    throw InputError(option + " " + text + ": expected " + kind +
                     " followed by a positive number (e.g. " + kind + "1)");
  name.type = *type;
  name.ordinal = std::stoi(number);
  return name;
}

}  // namespace sympathy::app
