// Checks of the errors that bad input must give.
#pragma once

#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <string>

#include <gtest/gtest.h>

#include "sympathy/core/errors.hpp"

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

// Writes `text` to FOLDER/TEST.EXTENSION in the temporary directory (TEST: the running test's
// name) and returns the path: an input file for one test.
inline std::string write_test_file(const std::string& folder, const std::string& extension,
                                   const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / folder;
  std::filesystem::create_directories(dir);
  const std::string path =
      (dir /
       (std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()) + extension))
          .string();
  std::ofstream(path) << text;
  return path;
}

// Each of `parts` occurs in `message`.
inline void expect_mentions(const std::string& message, std::initializer_list<std::string> parts) {
  for (const auto& p : parts)
    EXPECT_NE(message.find(p), std::string::npos) << "'" << p << "' not in: " << message;
}

}  // namespace sympathy::testing
