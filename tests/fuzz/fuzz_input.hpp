// What the fuzz targets share: the readers under test take a path, so each input is written to
// a file in a directory of the fuzzing process's own (under $TMPDIR, else /tmp; scripts/fuzz
// points TMPDIR into build-fuzz and removes it afterwards).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace sympathy::fuzz {

// Writes `size` bytes of `data` to the file `name` in this process's directory; returns its path.
inline std::string write_input(const std::uint8_t* data, std::size_t size,
                               const std::string& name) {
  static const std::string dir = [] {
    const char* tmp = std::getenv("TMPDIR");
    std::string pattern = std::string(tmp && *tmp ? tmp : "/tmp") + "/sympathy-fuzz-XXXXXX";
    if (!mkdtemp(pattern.data())) {
      std::perror("fuzz: mkdtemp");
      std::abort();
    }
    return pattern;
  }();
  const std::string path = dir + "/" + name;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
    std::perror(("fuzz: " + path).c_str());
    std::abort();
  }
  return path;
}

}  // namespace sympathy::fuzz
