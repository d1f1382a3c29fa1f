// Writers of equilibrium branches over the system's own names: one CSV row per point, streamed as
// each is found (index, parameter, states, unstable eigenvalues, residual, eigenvalues), and the
// branch as JSON (points, events with their Hopf data), which `continue --switch-at HB1 --parent`
// reads back.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/equilibrium_curve.hpp"
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

// A fold or Hopf curve of equilibria: `of` "equilibria", kind (LP, HB), both parameters, origin,
// stop, points (values, state, eigenvalues; kappa, omega, neutral_saddle and l1 on a Hopf curve)
// and its codimension-two points.
nlohmann::json equilibrium_curve_json(const EquilibriumCurve& curve);

// One CSV row per curve point: index, both parameters, the states, kappa, omega, neutral_saddle,
// lyapunov (NaN where they do not apply), residual and the eigenvalues (re, im).
class EquilibriumCurveCsvWriter {
 public:
  // Throws OutputError if `path` cannot be opened.
  EquilibriumCurveCsvWriter(const std::string& path, const OdeSystem& system,
                            const std::string& first, const std::string& second);
  void write(const EquilibriumCurvePoint& point);  // throws OutputError
  void close() { csv_.close(); }

 private:
  CsvWriter csv_;
  int n_;
};

}  // namespace sympathy
