#include "sympathy/continuation/equilibrium_output.hpp"

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

}  // namespace sympathy
