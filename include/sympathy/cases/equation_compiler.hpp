// An equation case file's system as native code: generated C++ (equation_codegen.hpp) compiled
// once with the C++ compiler that built sympathy into a shared library, cached by content, and
// loaded with dlopen through the library's C factory.
//
// The cache: a directory (SYMPATHY_CACHE_DIR, else $XDG_CACHE_HOME/sympathy, else
// ~/.cache/sympathy) with, per system, KEY.cpp (the generated source, for reading), KEY.so and
// KEY.manifest. KEY is the SHA-256 of the generated source, the compiler's path and identity,
// the flags, sympathy's version and the engine headers' hashes: a system, compiler or header
// change is a new entry, and equal systems share one (names are not in the source, so the same
// equations under other names reuse it). Entries are written atomically (a temporary file in
// the directory, then rename; the manifest last), so a reader never sees half an entry. Before
// anything is loaded, the manifest must name KEY and the library's SHA-256 must equal the
// manifest's; after dlopen, the library's own tag must be KEY, its ABI kEquationAbi and its
// binary interface (core/binary_interface.hpp: Eigen's allocation, sanitizers) the program's. An
// entry that fails a check before dlopen is rebuilt, never loaded (a library that fails after
// it, which its manifest vouched for, is closed and rebuilt).
//
// The cache is a security boundary (a library found there runs in this process): an entry is
// loaded only if the cache directory and every directory above it (but a root-owned sticky one,
// as /tmp) belong to this user or root and are writable by nobody else, and its library and
// manifest are regular files of this user's or root's that nobody else can write. The library is
// opened without following links, checked and hashed through that descriptor, and that
// descriptor is what dlopen loads (/proc/self/fd/N). A cache directory writable by others is
// refused, naming it; a new one is made with mode 0700; the compiler's output is made in a
// private (0700) directory and is mode 0644 before it is moved into place.
//
// The compiler runs without a shell (fork and exec, its arguments a list), on a source written
// by sympathy from expression trees; its output is kept in KEY.log on failure.
#pragma once

#include <memory>
#include <string>

#include "sympathy/cases/equation_case.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

// SYMPATHY_CACHE_DIR, else $XDG_CACHE_HOME/sympathy, else $HOME/.cache/sympathy.
std::string default_equation_cache_dir();

struct EquationBuild {
  std::shared_ptr<const OdeSystem> system;  // keeps its library loaded while it lives
  std::string key;                          // the cache key
  std::string library;                      // the path of the library loaded
  bool compiled = false;                    // false: taken from the cache
  std::string include_dir;                  // compiled: the engine headers it was compiled with
  std::string rebuilt_because;              // why an entry present was not used ("" if none)
  double seconds = 0.0;                     // generating, compiling (if) and loading
  std::string plugin;                       // the C++ plug-in's source ("" for equations)
};

// The system of `equations` with parameter values `values` as its defaults (in the case file's
// parameter order), from the cache at `cache_dir` ("" for default_equation_cache_dir()),
// compiled first if needed. Throws std::runtime_error when the compiler is missing or fails
// (with its first lines of output) or the engine's headers cannot be found.
EquationBuild build_equation_system(const EquationCase& equations, const Eigen::VectorXd& values,
                                    const std::string& cache_dir = "");

}  // namespace sympathy
