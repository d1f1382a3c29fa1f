#include "sympathy/continuation/branch_output.hpp"

#include "sympathy/core/output_file.hpp"

namespace sympathy {

namespace {

std::vector<std::string> csv_header(const OdeSystem& system, const std::string& parameter,
                                    const OrbitDescriber* describer) {
  std::vector<std::string> h{
      "index",     parameter,        "period",      "frequency",
      "stability", "unstable_count", "max_modulus", "trivial_multiplier_error",
      "residual",  "structural",     "iterations",  "step"};
  if (describer)
    for (const auto& g : describer->layout())
      for (const auto& label : g.labels) h.push_back(g.csv_prefix + label);
  for (int i = 0; i < system.dimension(); ++i) {
    h.push_back("mu" + std::to_string(i + 1) + "_re");
    h.push_back("mu" + std::to_string(i + 1) + "_im");
  }
  for (const auto& n : system.state_names()) h.push_back(n);
  return h;
}

}  // namespace

std::vector<double> as_vector(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

nlohmann::json multipliers_json(const FloquetAnalysis& floquet) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& m : floquet.multipliers) j.push_back({m.value.real(), m.value.imag()});
  return j;
}

nlohmann::json parameters_json(const OdeSystem& system, const ParameterValues& p) {
  nlohmann::json j = nlohmann::json::object();
  const auto names = system.parameter_names();
  for (int i = 0; i < static_cast<int>(names.size()); ++i) j[names[i]] = system.parameter(p, i);
  return j;
}

nlohmann::json stiffness_json(const StiffnessEstimate& e) {
  return {{"indicator", e.indicator},
          {"threshold", kStiffIndicator},
          {"stiff", e.indicator > kStiffIndicator},
          {"capped", e.capped},
          {"steps", e.steps},
          {"bdf_steps", e.bdf_steps},
          {"spectral_radius", e.rate},
          {"largest_h_rate", e.largest_h_rate},
          {"seconds", e.seconds}};
}

nlohmann::json orbit_json(const OdeSystem& system, const PeriodicOrbit& orbit,
                          const OrbitDescriber* describer) {
  const auto& f = orbit.floquet;
  nlohmann::json j;
  j["converged"] = orbit.converged();
  j["period"] = orbit.period;
  j["frequency"] = 1.0 / orbit.period;
  j["multipliers"] = multipliers_json(f);
  nlohmann::json moduli = nlohmann::json::array(), kinds = nlohmann::json::array();
  for (const auto& m : f.multipliers) {
    moduli.push_back(m.modulus());
    kinds.push_back(m.trivial ? "trivial" : m.structural ? "structural" : "");
  }
  j["moduli"] = moduli;
  j["multiplier_kinds"] = kinds;
  if (!orbit.subspace.is_whole_space()) {
    nlohmann::json symmetry = nlohmann::json::array();
    for (const auto& m : f.multipliers) symmetry.push_back(to_string(m.symmetry));
    j["multiplier_symmetry"] = symmetry;  // "keeps" or "breaks" the subspace's symmetry
    j["subspace"] = orbit.subspace.description();
  }
  if (!orbit.reduction.empty()) j["reduction"] = orbit.reduction;  // how a symmetry reduced it
  j["stable"] = f.stability == Stability::Stable;
  j["stability"] = to_string(f.stability);
  j["trivial_multiplier_error"] = f.trivial_error;
  j["residual"] = orbit.residual;
  j["family_dimension"] = orbit.family_dimension;
  j["segments"] = orbit.segments;
  if (orbit.segment_growth > 0.0) j["segment_growth"] = orbit.segment_growth;
  if (orbit.monodromy_growth > 0.0) j["monodromy_growth"] = orbit.monodromy_growth;
  j["state0"] = as_vector(orbit.state0);
  j["state_names"] = system.state_names();
  if (describer) {
    const std::vector<double> numbers = describer->describe(orbit);
    std::size_t k = 0;
    for (const auto& g : describer->layout()) {
      nlohmann::json group = nlohmann::json::object();
      for (const auto& label : g.labels) group[label] = k < numbers.size() ? numbers[k++] : NAN;
      j[g.name] = group;
    }
  }
  j["params"] = parameters_json(system, orbit.parameters);
  j["newton"] = {{"converged", orbit.newton.converged},
                 {"reason", orbit.newton.reason},
                 {"iterations", orbit.newton.iterations},
                 {"residual_norms", orbit.newton.residual_norms}};
  if (orbit.stiffness) j["stiffness"] = stiffness_json(*orbit.stiffness);
  return j;
}

nlohmann::json hopf_json(const HopfPoint& h) {
  nlohmann::json j;
  j["value"] = h.parameter;
  j["uncertainty"] = h.uncertainty;
  j["omega"] = h.omega;
  j["period"] = h.period;
  j["state"] = as_vector(h.state);
  j["eigenvector_re"] = as_vector(h.eigenvector.real());
  j["eigenvector_im"] = as_vector(h.eigenvector.imag());
  if (h.lyapunov) j["lyapunov"] = *h.lyapunov;
  if (h.c1) j["c1"] = {h.c1->real(), h.c1->imag()};
  j["criticality"] = describe_criticality(h.lyapunov);
  return j;
}

void add_description(nlohmann::json& j, const std::vector<OrbitDescriber::Group>& layout,
                     const std::vector<double>& description) {
  if (description.empty()) return;
  std::size_t k = 0;
  for (const auto& g : layout) {
    std::vector<double> numbers;
    for (std::size_t i = 0; i < g.labels.size() && k < description.size(); ++i)
      numbers.push_back(description[k++]);
    j[g.name] = numbers;
  }
}

nlohmann::json branch_json(const Branch& branch, const OrbitDescriber* describer) {
  nlohmann::json j;
  j["parameter"] = branch.parameter_name;
  j["stop_reason"] = branch.stop_reason;
  if (!branch.origin.empty()) j["origin"] = branch.origin;  // a switched branch: its event
  j["stop"] = to_string(branch.stop);
  if (branch.hopf_end) j["hopf_end"] = hopf_json(*branch.hopf_end);
  j["state_names"] = branch.state_names;
  j["parameter_values"] = as_vector(branch.start_values);  // every raw value the branch kept
  const auto layout = describer ? describer->layout() : std::vector<OrbitDescriber::Group>{};
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : branch.points) {
    const auto& f = p.orbit.floquet;
    nlohmann::json q;
    q["index"] = p.index;
    q["value"] = p.parameter;
    q["period"] = p.orbit.period;
    q["frequency"] = 1.0 / p.orbit.period;
    q["stable"] = f.stability == Stability::Stable;
    q["stability"] = to_string(f.stability);
    q["multipliers"] = multipliers_json(f);
    q["trivial_multiplier_error"] = f.trivial_error;
    q["residual"] = p.orbit.residual;
    q["segments"] = p.orbit.segments;
    if (p.orbit.segment_growth > 0.0) q["segment_growth"] = p.orbit.segment_growth;
    if (p.orbit.monodromy_growth > 0.0) q["monodromy_growth"] = p.orbit.monodromy_growth;
    q["structural"] = f.structural;
    q["state0"] = as_vector(p.orbit.state0);
    add_description(q, layout, p.description);
    points.push_back(q);
  }
  j["points"] = points;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : branch.events) {
    events.push_back({{"type", to_string(e.type)},
                      {"name", describe(e.type)},
                      {"value", e.parameter},
                      {"uncertainty", e.uncertainty},
                      {"bracket", e.bracket},
                      {"period", e.period},
                      {"multipliers", multipliers_json(e.floquet)},
                      {"crossing_multiplier", {e.crossing.real(), e.crossing.imag()}},
                      {"multiplicity", e.multiplicity},
                      {"located", e.located()},
                      {"location", to_string(e.location)},
                      {"symmetry", to_string(e.symmetry)},
                      {"trusted", e.trusted()},
                      {"note", e.note},
                      // What switching at it needs (switch_branch): the located orbit, the
                      // shooting unknowns and the branch's tangent there, the point before it.
                      {"state0", as_vector(e.state0)},
                      {"unknowns", as_vector(e.unknowns)},
                      {"tangent", as_vector(e.tangent)},
                      {"after_point", e.after_point}});
    add_description(events.back(), layout, e.description);
  }
  j["events"] = events;
  j["seconds"] = branch.seconds;
  j["flow"] = {{"integrations", branch.flow.calls},
               {"steps", branch.flow.steps},
               {"rhs_evaluations", branch.flow.rhs_evaluations},
               {"sensitivity_rhs_evaluations", branch.flow.variational_evaluations}};
  if (branch.stiffness) j["stiffness"] = stiffness_json(*branch.stiffness);
  return j;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  write_file_atomically(path, j.dump(1) + "\n");
}

BranchCsvWriter::BranchCsvWriter(const std::string& path, const OdeSystem& system,
                                 const std::string& parameter_name, const OrbitDescriber* describer)
    : csv_(path, csv_header(system, parameter_name, describer)) {
  if (describer)
    for (const auto& g : describer->layout()) described_ += g.labels.size();
}

void BranchCsvWriter::write(const ContinuationPoint& p) {
  const auto& f = p.orbit.floquet;
  std::vector<std::string> row{std::to_string(p.index),         format_double(p.parameter),
                               format_double(p.orbit.period),   format_double(1.0 / p.orbit.period),
                               to_string(f.stability),          std::to_string(f.unstable_count),
                               format_double(f.max_modulus),    format_double(f.trivial_error),
                               format_double(p.orbit.residual), std::to_string(f.structural),
                               std::to_string(p.iterations),    format_double(p.step)};
  for (std::size_t k = 0; k < described_; ++k)
    row.push_back(format_double(k < p.description.size() ? p.description[k] : NAN));
  for (const auto& m : f.multipliers) {
    row.push_back(format_double(m.value.real()));
    row.push_back(format_double(m.value.imag()));
  }
  for (int i = 0; i < p.orbit.state0.size(); ++i) row.push_back(format_double(p.orbit.state0[i]));
  csv_.row(row);
}

EventCsvWriter::EventCsvWriter(const std::string& path, const std::string& parameter_name)
    : csv_(path, {"type", parameter_name, "uncertainty", "period", "crossing_re", "crossing_im",
                  "multiplicity", "location", "trusted", "after_point", "note"}) {}

void EventCsvWriter::write(const Bifurcation& e) {
  csv_.row(std::vector<std::string>{
      to_string(e.type), format_double(e.parameter), format_double(e.uncertainty),
      format_double(e.period), format_double(e.crossing.real()), format_double(e.crossing.imag()),
      std::to_string(e.multiplicity), to_string(e.location), e.trusted() ? "yes" : "no",
      std::to_string(e.after_point), e.note});
}

}  // namespace sympathy
