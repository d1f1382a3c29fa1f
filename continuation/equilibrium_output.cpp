#include "sympathy/continuation/equilibrium_output.hpp"

#include <cmath>

#include "sympathy/continuation/branch_output.hpp"

namespace sympathy {

namespace {

nlohmann::json eigenvalues_json(const Eigen::VectorXcd& v) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& l : v) j.push_back({l.real(), l.imag()});
  return j;
}

std::vector<std::string> header(const OdeSystem& system, const std::string& parameter_name) {
  std::vector<std::string> h{"index", parameter_name};
  for (const auto& s : system.state_names()) h.push_back(s);
  h.insert(h.end(), {"unstable", "residual"});
  for (int k = 1; k <= system.dimension(); ++k) {
    h.push_back("lambda" + std::to_string(k) + "_re");
    h.push_back("lambda" + std::to_string(k) + "_im");
  }
  return h;
}

}  // namespace

nlohmann::json equilibrium_branch_json(const EquilibriumBranch& branch) {
  nlohmann::json j;
  j["kind"] = "equilibria";
  j["parameter"] = branch.parameter_name;
  j["stop"] = to_string(branch.stop);
  j["stop_reason"] = branch.stop_reason;
  j["state_names"] = branch.state_names;
  j["parameter_values"] = as_vector(branch.start_values);
  j["seconds"] = branch.seconds;
  if (!branch.origin.empty()) j["origin"] = branch.origin;
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : branch.points)
    points.push_back({{"index", p.index},
                      {"value", p.parameter},
                      {"state", as_vector(p.state)},
                      {"unstable", p.unstable},
                      {"residual", p.residual},
                      {"eigenvalues", eigenvalues_json(p.eigenvalues)}});
  j["points"] = points;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : branch.events) {
    nlohmann::json x{{"type", to_string(e.type)},
                     {"value", e.parameter},
                     {"uncertainty", e.uncertainty},
                     {"located", e.located},
                     {"state", as_vector(e.state)},
                     {"residual", e.residual},
                     {"eigenvalues", eigenvalues_json(e.eigenvalues)},
                     {"after_point", e.after_point},
                     {"tangent", as_vector(e.tangent)},
                     {"note", e.note}};
    if (e.hopf) x["hopf"] = hopf_json(*e.hopf);
    events.push_back(x);
  }
  j["events"] = events;
  return j;
}

EquilibriumCsvWriter::EquilibriumCsvWriter(const std::string& path, const OdeSystem& system,
                                           const std::string& parameter_name)
    : csv_(path, header(system, parameter_name)), n_(system.dimension()) {}

void EquilibriumCsvWriter::write(const EquilibriumPoint& p) {
  std::vector<double> row{static_cast<double>(p.index), p.parameter};
  for (int i = 0; i < n_; ++i) row.push_back(p.state[i]);
  row.push_back(p.unstable);
  row.push_back(p.residual);
  for (int i = 0; i < n_; ++i) {
    row.push_back(p.eigenvalues[i].real());
    row.push_back(p.eigenvalues[i].imag());
  }
  csv_.row(row);
}

namespace {

// JSON has no NaN: a number that does not apply is null.
nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

nlohmann::json coefficients_json(const std::vector<std::pair<std::string, double>>& c) {
  nlohmann::json j = nlohmann::json::object();
  for (const auto& [name, value] : c) j[name] = value;
  return j;
}

double omega_of(const EquilibriumCurvePoint& p) {
  return p.kappa > 0.0 ? std::sqrt(p.kappa) : std::nan("");
}

nlohmann::json curve_point_json(const EquilibriumCurvePoint& p) {
  return {{"index", p.index},
          {"first", p.first},
          {"second", p.second},
          {"state", as_vector(p.state)},
          {"eigenvalues", eigenvalues_json(p.eigenvalues)},
          {"kappa", number_or_null(p.kappa)},
          {"omega", number_or_null(omega_of(p))},
          {"neutral_saddle", p.neutral_saddle},
          {"lyapunov", number_or_null(p.lyapunov)},
          {"residual", p.residual}};
}

}  // namespace

nlohmann::json equilibrium_curve_json(const EquilibriumCurve& curve) {
  nlohmann::json j;
  j["kind"] = to_string(curve.kind);
  j["of"] = "equilibria";
  add_curve_frame(j, curve);
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : curve.points) points.push_back(curve_point_json(p));
  j["points"] = points;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : curve.events)
    events.push_back({{"type", e.type},
                      {"description", e.description},
                      {"first", e.first},
                      {"second", e.second},
                      {"uncertainty", e.uncertainty},
                      {"located", e.located},
                      {"after_point", e.after_point},
                      {"note", e.note},
                      {"coefficients", coefficients_json(e.coefficients)},
                      {"point", curve_point_json(e.at)}});
  j["events"] = events;
  j["seconds"] = curve.seconds;
  return j;
}

EquilibriumCurveCsvWriter::EquilibriumCurveCsvWriter(const std::string& path,
                                                     const OdeSystem& system,
                                                     const std::string& first,
                                                     const std::string& second)
    : csv_(path,
           [&] {
             std::vector<std::string> h{"index", first, second};
             for (const auto& s : system.state_names()) h.push_back(s);
             h.insert(h.end(), {"kappa", "omega", "neutral_saddle", "lyapunov", "residual"});
             for (int k = 1; k <= system.dimension(); ++k) {
               h.push_back("lambda" + std::to_string(k) + "_re");
               h.push_back("lambda" + std::to_string(k) + "_im");
             }
             return h;
           }()),
      n_(system.dimension()) {}

void EquilibriumCurveCsvWriter::write(const EquilibriumCurvePoint& p) {
  std::vector<double> row{static_cast<double>(p.index), p.first, p.second};
  for (int i = 0; i < n_; ++i) row.push_back(p.state[i]);
  row.insert(row.end(),
             {p.kappa, omega_of(p), p.neutral_saddle ? 1.0 : 0.0, p.lyapunov, p.residual});
  for (int i = 0; i < n_; ++i) {
    row.push_back(p.eigenvalues[i].real());
    row.push_back(p.eigenvalues[i].imag());
  }
  csv_.row(row);
}

}  // namespace sympathy
