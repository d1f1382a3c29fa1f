// A study or map file's `escapement` key: a metronome case's escapement instead of its file's
// (the paper's Fig. 8 or a stability map on its own escapement, eq. 2, beside the smoothed one).
#pragma once

#include <optional>

#include <toml++/toml.h>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/toml_reader.hpp"

namespace sympathy::app {

// The escapement `root` names (nullopt without the key); InputError naming the line and the key
// for a name that is none.
std::optional<Escapement> read_escapement_key(const TomlReader& in, const toml::table& root);

}  // namespace sympathy::app
