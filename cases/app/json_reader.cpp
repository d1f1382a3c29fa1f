#include "cases/app/json_reader.hpp"

#include <fstream>

namespace sympathy::app {

JsonReader::JsonReader(std::string path, std::string written_by)
    : path_(std::move(path)), written_by_(std::move(written_by)) {
  std::ifstream in(path_);
  if (!in) throw InputError(path_ + ": cannot be read");
  try {
    root_ = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path_ + ": not JSON (" + e.what() + ")");
  }
}

const nlohmann::json& JsonReader::key(const nlohmann::json& j, const std::string& name,
                                      const std::string& where) const {
  if (!j.is_object() || !j.contains(name))
    throw InputError(where + ": key '" + name + "' is missing; expected " + written_by_);
  return j.at(name);
}

Eigen::VectorXd JsonReader::numbers(const nlohmann::json& j, const std::string& where,
                                    int size) const {
  if (!j.is_array()) throw InputError(where + ": expected a list of numbers");
  Eigen::VectorXd v(static_cast<int>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_number()) throw InputError(where + ": expected a list of numbers");
    v[static_cast<int>(i)] = j[i].get<double>();
  }
  if (size >= 0 && v.size() != size)
    throw InputError(where + ": expected " + std::to_string(size) + " numbers, got " +
                     std::to_string(v.size()));
  return v;
}

}  // namespace sympathy::app
