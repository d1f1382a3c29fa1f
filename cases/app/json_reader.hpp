// A JSON file a command reads back (continue --json, equilibria --json): parsed whole, its keys
// and lists checked, every message naming the file, the key and what writes such a file.
#pragma once

#include <string>

#include <Eigen/Dense>
#include <nlohmann/json.hpp>

#include "sympathy/core/errors.hpp"

namespace sympathy::app {

class JsonReader {
 public:
  // Reads and parses `path`; InputError if it cannot be read or is not JSON. `written_by` ends
  // the messages: "expected a branch JSON written by sympathy continue --json".
  JsonReader(std::string path, std::string written_by);

  const nlohmann::json& root() const { return root_; }
  const std::string& path() const { return path_; }
  // j[name]; InputError "WHERE: key 'NAME' is missing; expected WRITTEN_BY".
  const nlohmann::json& key(const nlohmann::json& j, const std::string& name,
                            const std::string& where) const;
  // A list of numbers (of `size` entries unless size < 0); InputError naming `where`.
  Eigen::VectorXd numbers(const nlohmann::json& j, const std::string& where, int size = -1) const;
  // read(root), nlohmann's type errors turned into InputError naming the file.
  template <class F>
  auto read(F read) const {
    try {
      return read(root_);
    } catch (const nlohmann::json::exception& e) {
      throw InputError(path_ + ": a value of the wrong type (" + e.what() + "); expected " +
                       written_by_);
    }
  }

 private:
  std::string path_, written_by_;
  nlohmann::json root_;
};

}  // namespace sympathy::app
