// SHA-256 (FIPS 180-4), for the content keys and integrity checks of the equation cache
// (equation_compiler.hpp). Written here because no dependency of sympathy provides one; held to
// the standard's test vectors in tests/cases/sha256_test.cpp.
#pragma once

#include <string>
#include <string_view>

namespace sympathy {

// The digest of `data` as 64 lowercase hexadecimal digits.
std::string sha256_hex(std::string_view data);

}  // namespace sympathy
