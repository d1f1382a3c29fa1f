// Names in messages and indexed parameter names, shared by case files, models, fits and the CLI.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sympathy/core/text.hpp"  // join, format_number

namespace sympathy {

// Splits an indexed name, "d12" into ("d", 12); index 0 when there is no numeric suffix (or
// one with a leading zero, which no index has).
std::pair<std::string, int> split_index(const std::string& name);

}  // namespace sympathy
