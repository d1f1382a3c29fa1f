#include "cases/names.hpp"

#include <sstream>

#include <cctype>

namespace sympathy {

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

std::pair<std::string, int> split_index(const std::string& name) {
  std::size_t k = name.size();
  while (k > 0 && std::isdigit(static_cast<unsigned char>(name[k - 1]))) --k;
  if (k == name.size() || k == 0 || name[k] == '0') return {name, 0};
  return {name.substr(0, k), std::stoi(name.substr(k))};
}

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

}  // namespace sympathy
