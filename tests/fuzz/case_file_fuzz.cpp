// Fuzz target: the case-file reader. Any input either loads or is refused with an InputError
// (naming the file, the line and the key); a crash, a sanitizer report or any other exception
// is a finding. A case that loads is used as the commands use it: each parameter set applied
// (CaseFile::spec), each start's initial state, and for small models the model built and each
// start's invariant subspace checked against it.
#include <cstddef>
#include <cstdint>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/core/errors.hpp"
#include "tests/fuzz/fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = sympathy::fuzz::write_input(data, size, "case.toml");
  try {
    const sympathy::CaseFile file = sympathy::CaseFile::load(path);
    file.state_names();
    auto sets = file.parameter_set_names();
    sets.push_back("");  // the file's default
    for (const auto& set : sets) {
      try {
        const sympathy::ModelSpec spec = file.spec(set);
        if (spec.metronomes.size() > 8) continue;  // keep an input's run short
        const sympathy::MetronomeModel model(spec);
        for (const auto& name : file.start_names()) {
          const sympathy::StartSpec& start = file.start(name);
          file.initial_state(&start);
          try {
            file.invariant_subspace(start, model);
          } catch (const sympathy::InputError&) {
          }
        }
      } catch (const sympathy::InputError&) {
      }
    }
  } catch (const sympathy::InputError&) {
    // Bad input refused: the expected outcome.
  }
  return 0;
}
