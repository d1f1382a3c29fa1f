#include "sympathy/core/text.hpp"

#include <cmath>
#include <exception>
#include <sstream>

namespace sympathy {

std::string join(const std::vector<std::string>& items, const std::string& separator) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : separator) + s;
  return out;
}

std::string format_number(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::optional<double> whole_number(const std::string& text) {
  std::size_t used = 0;
  double x = 0.0;
  try {
    x = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  if (used != text.size()) return std::nullopt;
  return x;
}

std::optional<double> finite_number(const std::string& text) {
  const auto x = whole_number(text);
  if (!x || !std::isfinite(*x)) return std::nullopt;
  return x;
}

}  // namespace sympathy
