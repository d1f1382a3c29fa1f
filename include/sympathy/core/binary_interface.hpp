// What two separately compiled pieces of sympathy must agree on to share objects: a system
// compiled at run time (an equation case file's, cases/equation_compiler.hpp) is created in its
// own shared library and used, resized and freed by the program. Eigen's memory handling depends
// on compile flags: under AddressSanitizer (__SANITIZE_ADDRESS__) or with wider vectors
// (-mavx: 32-byte alignment) it allocates with its own aligned malloc, whose blocks the plain
// free of a library compiled otherwise must never receive (found by scripts/sanitize: a
// heap-buffer-overflow in handmade_aligned_free when the program was sanitized and the library
// not). Both sides compile this string from their own macros; a library whose string differs
// from the program's is not used.
#pragma once

#include <Eigen/Core>

#define SYMPATHY_BINARY_INTERFACE_TEXT2(x) #x
#define SYMPATHY_BINARY_INTERFACE_TEXT(x) SYMPATHY_BINARY_INTERFACE_TEXT2(x)
#if defined(__SANITIZE_ADDRESS__)
#define SYMPATHY_BINARY_INTERFACE_ASAN " asan"
#else
#define SYMPATHY_BINARY_INTERFACE_ASAN ""
#endif

namespace sympathy {

inline constexpr const char* kBinaryInterface =
    "eigen " SYMPATHY_BINARY_INTERFACE_TEXT(EIGEN_WORLD_VERSION) "." SYMPATHY_BINARY_INTERFACE_TEXT(
        EIGEN_MAJOR_VERSION) "." SYMPATHY_BINARY_INTERFACE_TEXT(EIGEN_MINOR_VERSION) " align " SYMPATHY_BINARY_INTERFACE_TEXT(EIGEN_DEFAULT_ALIGN_BYTES) " malloc-aligned " SYMPATHY_BINARY_INTERFACE_TEXT(EIGEN_MALLOC_ALREADY_ALIGNED) " cxx11-abi " SYMPATHY_BINARY_INTERFACE_TEXT(_GLIBCXX_USE_CXX11_ABI) SYMPATHY_BINARY_INTERFACE_ASAN;

}  // namespace sympathy
