// Fuzz target: the equation case file reader (cases/equation_case.hpp) and the code generator
// behind it. Any input either loads or is refused with an InputError (naming the file, line and
// column); a crash, a sanitizer report or any other exception is a finding. A file that loads is
// used as the commands use it: every parameter set's values, every start's state, and the C++
// generated from it (not compiled: that takes seconds), which must not depend on the file's
// names: the same system with every name replaced must give the same source byte for byte.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <map>
#include <string>

#include "sympathy/cases/equation_case.hpp"
#include "sympathy/cases/equation_codegen.hpp"
#include "sympathy/core/errors.hpp"
#include "tests/fuzz/fuzz_input.hpp"

namespace {

void rename(sympathy::Expression& e, const std::map<std::string, std::string>& names) {
  if (e.kind == sympathy::Expression::Kind::Name && names.count(e.name)) e.name = names.at(e.name);
  for (auto& o : e.operands) rename(o, names);
}

// The system with its names replaced by n0, n1, ... (t and pi stay).
sympathy::EquationSystem renamed(sympathy::EquationSystem system) {
  std::map<std::string, std::string> names;
  auto fresh = [&](std::string& name) {
    const std::string other = "n" + std::to_string(names.size());
    names[name] = other;
    name = other;
  };
  for (auto& s : system.states) fresh(s.name);
  for (auto& p : system.parameters) fresh(p.name);
  for (auto& w : system.intermediates) fresh(w.name);
  for (auto& w : system.intermediates) rename(w.tree, names);
  for (auto& d : system.derivatives) {
    d.name = names.at(d.name);
    rename(d.tree, names);
  }
  for (auto& zone : system.steep) {
    rename(zone.width, names);
    if (zone.scale) rename(*zone.scale, names);
  }
  for (auto& impact : system.impacts) {
    rename(impact.surface, names);
    for (auto& [state, value] : impact.reset) rename(value, names);
  }
  if (system.forcing_period) rename(*system.forcing_period, names);
  return system;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = sympathy::fuzz::write_input(data, size, "equations.toml");
  try {
    const sympathy::EquationCase file = sympathy::EquationCase::load(path);
    auto sets = file.parameter_set_names();
    sets.push_back("");  // the file's default
    for (const auto& set : sets) file.parameter_values(set);
    file.initial_state(nullptr);
    for (const auto& name : file.start_names()) file.initial_state(&file.start(name));
    const std::string source = sympathy::generate_equation_source(file.system());
    if (sympathy::generate_equation_source(renamed(file.system())) != source) std::abort();
  } catch (const sympathy::InputError&) {
    // Bad input refused: the expected outcome.
  }
  return 0;
}
