#include "cases/app/saved_start_key.hpp"

#include <filesystem>

#include "sympathy/core/errors.hpp"

namespace sympathy::app {

std::optional<SavedStart> read_saved_start_keys(const TomlReader& in, const toml::node& entry,
                                                const std::string& prefix,
                                                const std::string& parent_kind,
                                                std::initializer_list<const char*> not_beside) {
  const auto& t = *entry.as_table();
  if (!t.get("parent") && !t.get("from_point")) return std::nullopt;
  for (const char* key : {"parent", "from_point"})
    if (!t.get(key))
      throw InputError(in.where(entry) + ": key '" + prefix + key +
                       "' is missing; expected parent (" + parent_kind +
                       ") and from_point (a point's index or an event, UZ1) together");
  const toml::node& n = *t.get("from_point");
  for (const char* own : not_beside)
    if (t.get(own))
      in.fail(n, prefix + "from_point",
              std::string("no ") + own +
                  " beside it (the saved point is the start, at its own parameter values)");
  if (!n.is_integer() && !n.is_string())
    in.fail(n, prefix + "from_point", "a point's index or an event's name (UZ1, PD2)");
  const std::string what = n.is_integer() ? std::to_string(in.integer(n, prefix + "from_point"))
                                          : in.string(n, prefix + "from_point");
  return SavedStart{(std::filesystem::path(in.path()).parent_path() /
                     in.string(*t.get("parent"), prefix + "parent"))
                        .lexically_normal()
                        .string(),
                    what};
}

}  // namespace sympathy::app
