// A study or map file's `parent` and `from_point` keys: a start from a point or event an earlier
// run saved, as --parent FILE --from-point POINT (saved_start.hpp reads the file, with the case).
#pragma once

#include <initializer_list>
#include <optional>
#include <string>

#include <toml++/toml.h>

#include "cases/app/saved_start.hpp"
#include "sympathy/cases/toml_reader.hpp"

namespace sympathy::app {

// The table `entry`'s saved start (the path relative to the file `in` reads); nullopt without
// either key. InputError naming the line and the key for one key without the other (`parent_kind`
// says what parent names: "a branch or curve JSON"), a from_point that is neither a point's index
// nor an event's name, or one of `not_beside` (keys that give a start of their own) beside them.
std::optional<SavedStart> read_saved_start_keys(const TomlReader& in, const toml::node& entry,
                                                const std::string& prefix,
                                                const std::string& parent_kind,
                                                std::initializer_list<const char*> not_beside);

}  // namespace sympathy::app
