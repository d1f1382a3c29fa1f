#include "sympathy/cases/names.hpp"

#include <sstream>

#include <cctype>

namespace sympathy {

std::pair<std::string, int> split_index(const std::string& name) {
  std::size_t k = name.size();
  while (k > 0 && std::isdigit(static_cast<unsigned char>(name[k - 1]))) --k;
  if (k == name.size() || k == 0 || name[k] == '0') return {name, 0};
  return {name.substr(0, k), std::stoi(name.substr(k))};
}

}  // namespace sympathy
