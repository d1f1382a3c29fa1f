// Fuzz target: the CSV reader of recordings (sympathy::read_csv) and, on what it accepts, the
// recording reader on top of it (read_recording: a time column, state columns, increasing
// times). Any input either loads or is refused with an InputError; a crash, a sanitizer report or
// any other exception is a finding.
#include <cstddef>
#include <cstdint>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/recording.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = sympathy::fuzz::write_input(data, size, "recording.csv");
  try {
    sympathy::read_csv(path);
    sympathy::read_recording(path, {"x", "th1", "th2", "vx", "vth1", "vth2"});
  } catch (const sympathy::InputError&) {
    // Bad input refused: the expected outcome.
  }
  return 0;
}
