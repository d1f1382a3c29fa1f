// Small pieces of text and timing for messages and reports, shared by every layer.
#pragma once

#include <chrono>
#include <optional>
#include <string>
#include <vector>

namespace sympathy {

// "a, b, c": a list of names for a message.
std::string join(const std::vector<std::string>& items, const std::string& separator = ", ");

// A number for a message: 12 significant digits, no trailing zeros.
std::string format_number(double v);

// `text` as a number (std::stod's forms, "inf" and "nan" among them): nullopt unless all of it
// is one. The one reader of a number from a word of text: options, case and data files, journals.
std::optional<double> whole_number(const std::string& text);
// The same, and finite.
std::optional<double> finite_number(const std::string& text);

// Wall time since construction.
class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace sympathy
