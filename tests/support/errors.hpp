// Checks of the errors that bad input must give.
#pragma once

#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "core/errors.hpp"

namespace sympathy::testing {

// The message of the InputError that `f` throws; fails the test if it throws none.
template <class F>
std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

// Each of `parts` occurs in `message`.
inline void expect_mentions(const std::string& message, std::initializer_list<std::string> parts) {
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' not in: " << message;
}

}  // namespace sympathy::testing
