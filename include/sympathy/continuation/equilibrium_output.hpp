// Writers of equilibrium branches over the system's own names: one CSV row per point, streamed as
// each is found (index, parameter, states, unstable eigenvalues, residual, eigenvalues), and the
// branch as JSON (points, events with their Hopf data), which `continue --switch-at HB1 --parent`
// reads back.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy {

nlohmann::json equilibrium_branch_json(const EquilibriumBranch& branch);

class EquilibriumCsvWriter {
 public:
  // Throws OutputError if `path` cannot be opened.
  EquilibriumCsvWriter(const std::string& path, const OdeSystem& system,
                       const std::string& parameter_name);
  void write(const EquilibriumPoint& point);  // throws OutputError
  void close() { csv_.close(); }

 private:
  CsvWriter csv_;
  int n_;
};

}  // namespace sympathy
