// Writers of orbits and branches over the system's own state and parameter names, below every
// front end: a branch's CSV streamed point by point (one row per point, written whole and
// flushed: a run that stops keeps every point before it), JSON for an orbit and a branch, and a
// JSON file written whole and atomically (core/output_file.hpp). A model's own columns (phases,
// amplitudes) come from its OrbitDescriber, already in each point's description.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy {

// [[re, im], ...]
nlohmann::json multipliers_json(const FloquetAnalysis& floquet);
// [v0, v1, ...]: a state, a tangent, parameter values.
std::vector<double> as_vector(const Eigen::VectorXd& v);
// {name: value} of every named parameter of the system at p.
nlohmann::json parameters_json(const OdeSystem& system, const ParameterValues& p);

// A Hopf point: its parameter value and uncertainty, omega, period, state, eigenvector (real and
// imaginary parts), first Lyapunov coefficient and criticality.
nlohmann::json hopf_json(const HopfPoint& hopf);

// The stiffness measured at an orbit's or branch's start (OrbitOptions::switch_when_stiff):
// indicator, threshold, stiff (BDF took over), capped, both step counts, the spectral radius and
// the largest h rho(J), and what the measurement cost.
nlohmann::json stiffness_json(const StiffnessEstimate& estimate);

// An orbit: period, multipliers (with moduli and kinds), stability, accuracy, state, parameter
// values, Newton's summary, the stiffness where it was measured, and the describer's groups as
// objects {label: value}.
nlohmann::json orbit_json(const OdeSystem& system, const PeriodicOrbit& orbit,
                          const OrbitDescriber* describer = nullptr);

// A branch: its parameter, stop reason, state names, points (with the describer's groups as
// lists, from each point's description), located events, run time, integration work and the
// stiffness measured at its start (where it was).
nlohmann::json branch_json(const Branch& branch, const OrbitDescriber* describer = nullptr);
// The fields every two-parameter curve's JSON has, a curve of cycles or of equilibria: both
// parameters' names, origin, stop, state names, parameter values and the window.
template <class Curve>
void add_curve_frame(nlohmann::json& j, const Curve& curve) {
  j["first"] = curve.first_name;
  j["second"] = curve.second_name;
  j["origin"] = curve.origin;
  j["stop"] = to_string(curve.stop);
  j["stop_reason"] = curve.stop_reason;
  j["state_names"] = curve.state_names;
  j["parameter_values"] = as_vector(curve.start_values);
  j["window"] = {{curve.first_name, {curve.options.first_lower, curve.options.first_upper}},
                 {curve.second_name, {curve.options.second_lower, curve.options.second_upper}}};
}
// A describer's numbers as its groups (JSON key per group, a list of numbers each); nothing when
// the orbit was not described.
void add_description(nlohmann::json& j, const std::vector<OrbitDescriber::Group>& layout,
                     const std::vector<double>& description);

// The JSON written to `path` whole and atomically; throws OutputError.
void write_json(const std::string& path, const nlohmann::json& j);

// One CSV row per point: index, the parameter, period, frequency, stability, accuracy, the
// describer's columns, the multipliers (re, im) and the orbit's initial state (any point can seed
// a new run).
class BranchCsvWriter {
 public:
  // Throws OutputError if `path` cannot be opened.
  BranchCsvWriter(const std::string& path, const OdeSystem& system,
                  const std::string& parameter_name, const OrbitDescriber* describer = nullptr);
  void write(const ContinuationPoint& point);  // throws OutputError
  void close() { csv_.close(); }

 private:
  CsvWriter csv_;
  std::size_t described_ = 0;  // the describer's columns
};

// One CSV row per located event, written as each is found (a run that is killed keeps every
// bifurcation located before): type, the parameter value, its bracket, period, the crossing
// multiplier, multiplicity, how location ended, trust, the point before it and the note.
class EventCsvWriter {
 public:
  EventCsvWriter(const std::string& path, const std::string& parameter_name);
  void write(const Bifurcation& event);  // throws OutputError
  void close() { csv_.close(); }

 private:
  CsvWriter csv_;
};

}  // namespace sympathy
