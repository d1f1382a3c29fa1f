// Fuzz target: the basins-file reader (app/basins_file.cpp, as `sympathy basins` reads its
// argument). Any input either loads or is refused with an InputError; a crash, a sanitizer
// report or any other exception is a finding.
#include <cstddef>
#include <cstdint>

#include "cases/app/basins_file.hpp"
#include "sympathy/core/errors.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = sympathy::fuzz::write_input(data, size, "basins.toml");
  try {
    sympathy::app::load_basins_file(path);
  } catch (const sympathy::InputError&) {
    // Bad input refused: the expected outcome.
  }
  return 0;
}
