#include "cases/app/escapement_key.hpp"

namespace sympathy::app {

std::optional<Escapement> read_escapement_key(const TomlReader& in, const toml::table& root) {
  const toml::node* n = root.get("escapement");
  if (!n) return std::nullopt;
  const auto escapement = escapement_named(in.string(*n, "escapement"));
  if (!escapement) in.fail(*n, "escapement", "\"half\", \"double\" or \"impulsive\"");
  return escapement;
}

}  // namespace sympathy::app
