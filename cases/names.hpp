// Names in messages and indexed parameter names, shared by case files, models, fits and the CLI.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace sympathy {

// "a, b, c": a list of names for a message.
std::string join(const std::vector<std::string>& items, const std::string& separator = ", ");

// Splits an indexed name, "d12" into ("d", 12); index 0 when there is no numeric suffix (or
// one with a leading zero, which no index has).
std::pair<std::string, int> split_index(const std::string& name);

// A number for a message: 12 significant digits, no trailing zeros.
std::string format_number(double v);

}  // namespace sympathy
