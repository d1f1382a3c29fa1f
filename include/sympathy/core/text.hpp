// Small pieces of text and timing for messages and reports, shared by every layer.
#pragma once

#include <chrono>
#include <string>
#include <vector>

namespace sympathy {

// "a, b, c": a list of names for a message.
std::string join(const std::vector<std::string>& items, const std::string& separator = ", ");

// A number for a message: 12 significant digits, no trailing zeros.
std::string format_number(double v);

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
