#include "python_results.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <utility>

#include <pybind11/complex.h>
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "sympathy/continuation/branch_output.hpp"

namespace sympathy::python {

namespace {

py::object with_fields(const py::dict& fields) {
  return py::module_::import("types").attr("SimpleNamespace")(**fields);
}

// The stiffness measured at a start, with the JSON's fields (continuation/branch_output.hpp's
// stiffness_json: one list of names for both), or None where none was measured (a method
// given, or BDF asked for).
py::object stiffness_result(const std::optional<StiffnessEstimate>& e) {
  if (!e) return py::none();
  const py::dict fields = py::module_::import("json").attr("loads")(stiffness_json(*e).dump());
  return with_fields(fields);
}

// The describer's groups (amplitudes, phase_differences, ...) of one orbit: a dict by label each.
void add_description(py::dict& fields, const OrbitDescriber& describer,
                     const std::vector<double>& numbers) {
  std::size_t k = 0;
  for (const auto& group : describer.layout()) {
    py::dict values;
    for (const auto& label : group.labels)
      values[py::str(label)] = k < numbers.size() ? numbers[k++] : std::nan("");
    fields[py::str(group.name)] = values;
  }
}

}  // namespace

py::array vector_array(const Eigen::VectorXd& v) {
  py::array_t<double> a(v.size());
  std::copy(v.data(), v.data() + v.size(), a.mutable_data());
  return a;
}

py::array matrix_array(const std::vector<Eigen::VectorXd>& rows, int columns) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(columns)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (int j = 0; j < columns; ++j)
      m(i, j) = j < rows[i].size() ? rows[i][j] : std::numeric_limits<double>::quiet_NaN();
  return a;
}

py::array multiplier_array(const FloquetAnalysis& floquet) {
  py::array_t<std::complex<double>> a(static_cast<py::ssize_t>(floquet.multipliers.size()));
  for (std::size_t i = 0; i < floquet.multipliers.size(); ++i)
    a.mutable_data()[i] = floquet.multipliers[i].value;
  return a;
}

namespace {

// Multipliers of each of `rows` as a 2-D complex array (NaN where a row has fewer).
template <typename Row, typename Multipliers>
py::array complex_rows(const std::vector<Row>& rows, Multipliers of) {
  std::size_t columns = 0;
  for (const auto& r : rows) columns = std::max(columns, of(r).size());
  py::array_t<std::complex<double>> a(
      {static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(columns)});
  auto m = a.mutable_unchecked<2>();
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto values = of(rows[i]);
    for (std::size_t j = 0; j < columns; ++j)
      m(i, j) = j < values.size() ? values[j] : std::complex<double>(std::nan(""), std::nan(""));
  }
  return a;
}

std::vector<std::complex<double>> values_of(const FloquetAnalysis& f) {
  std::vector<std::complex<double>> v;
  for (const auto& m : f.multipliers) v.push_back(m.value);
  return v;
}

// One field of every row as a 1-D array.
template <typename Row, typename Field>
py::array column_of(const std::vector<Row>& rows, Field field) {
  std::vector<decltype(field(std::declval<const Row&>()))> c;
  c.reserve(rows.size());
  for (const auto& r : rows) c.push_back(field(r));
  return py::array(py::cast(c));
}

}  // namespace

py::object orbit_result(const OdeSystem& system, const PeriodicOrbit& orbit,
                        const OrbitDescriber& describer) {
  const FloquetAnalysis& f = orbit.floquet;
  std::vector<double> moduli;
  std::vector<std::string> kinds, symmetry;
  for (const auto& m : f.multipliers) {
    moduli.push_back(std::abs(m.value));
    kinds.push_back(m.trivial ? "trivial" : m.structural ? "structural" : "");
    symmetry.push_back(to_string(m.symmetry));
  }
  py::dict parameters;
  const auto names = system.parameter_names();
  for (int i = 0; i < static_cast<int>(names.size()); ++i)
    parameters[py::str(names[i])] = system.parameter(orbit.parameters, i);
  py::dict newton;
  newton["iterations"] = orbit.newton.iterations;
  newton["residuals"] = orbit.newton.residual_norms;
  newton["outcome"] = to_string(orbit.newton.outcome);
  newton["reason"] = orbit.newton.reason;
  py::dict fields;
  fields["converged"] = orbit.converged();
  fields["period"] = orbit.period;
  fields["frequency"] = orbit.period > 0.0 ? 1.0 / orbit.period : 0.0;
  fields["state0"] = vector_array(orbit.state0);
  fields["state_names"] = system.state_names();
  fields["multipliers"] = multiplier_array(f);
  fields["moduli"] = moduli;
  fields["kinds"] = kinds;
  fields["symmetry"] = symmetry;
  fields["stable"] = f.stability == Stability::Stable;
  fields["stability"] = to_string(f.stability);
  fields["unstable_count"] = f.unstable_count;
  fields["max_modulus"] = f.max_modulus;
  fields["residual"] = orbit.residual;
  fields["trivial_multiplier_error"] = f.trivial_error;
  fields["family_dimension"] = orbit.family_dimension;
  fields["newton"] = with_fields(newton);
  fields["segments"] = orbit.segments;
  fields["stiffness"] = stiffness_result(orbit.stiffness);
  fields["reduction"] = orbit.reduction;
  fields["parameters"] = parameters;
  fields["seconds"] = orbit.seconds;
  // Described only where there is an orbit: the describer integrates one period of it.
  add_description(fields, describer,
                  orbit.converged() ? describer.describe(orbit) : std::vector<double>());
  return with_fields(fields);
}

py::object point_result(const ContinuationPoint& p) {
  py::dict fields;
  fields["index"] = p.index;
  fields["value"] = p.parameter;
  fields["period"] = p.orbit.period;
  fields["stability"] = to_string(p.orbit.floquet.stability);
  fields["max_modulus"] = p.orbit.floquet.max_modulus;
  fields["step"] = p.step;
  fields["iterations"] = p.iterations;
  return with_fields(fields);
}

py::object event_result(const Bifurcation& e) {
  py::dict fields;
  fields["type"] = to_string(e.type);
  fields["name"] = describe(e.type);
  fields["value"] = e.parameter;
  fields["uncertainty"] = e.uncertainty;
  fields["bracket"] = e.bracket;
  fields["period"] = e.period;
  fields["multipliers"] = multiplier_array(e.floquet);
  fields["crossing"] = e.crossing;
  fields["multiplicity"] = e.multiplicity;
  fields["located"] = e.located();
  fields["location"] = to_string(e.location);
  fields["symmetry"] = to_string(e.symmetry);
  fields["trusted"] = e.trusted();
  fields["note"] = e.note;
  fields["state0"] = vector_array(e.state0);
  fields["after_point"] = e.after_point;
  return with_fields(fields);
}

namespace {

// The describer's groups along `points` (branch or curve points, each with its `description`):
// a dict of arrays by label each (phase_differences["th2"], max["x"]); NaN where a point was not
// described.
template <class Point>
void add_described_columns(py::dict& arrays, const std::vector<Point>& points,
                           const OrbitDescriber& describer) {
  std::size_t offset = 0;
  for (const auto& group : describer.layout()) {
    py::dict values;
    for (const auto& label : group.labels) {
      std::vector<double> c;
      for (const auto& p : points)
        c.push_back(offset < p.description.size() ? p.description[offset] : std::nan(""));
      values[py::str(label)] = py::array(py::cast(c));
      ++offset;
    }
    arrays[py::str(group.name)] = values;
  }
}

}  // namespace

py::object branch_result(const Branch& branch, const OrbitDescriber& describer) {
  const auto& points = branch.points;
  const std::size_t n = points.size();
  auto column = [&](auto value) {
    std::vector<decltype(value(points.front()))> c;
    c.reserve(n);
    for (const auto& p : points) c.push_back(value(p));
    return py::array(py::cast(c));
  };
  py::dict arrays;
  std::vector<std::string> stability;
  std::vector<Eigen::VectorXd> states, multipliers_re, multipliers_im, described;
  int dimension = static_cast<int>(branch.state_names.size()), count = 0;
  for (const auto& p : points) {
    stability.push_back(to_string(p.orbit.floquet.stability));
    states.push_back(p.orbit.state0);
    count = std::max(count, static_cast<int>(p.orbit.floquet.multipliers.size()));
  }
  {  // one array per field (empty ones for a branch that never started)
    arrays["index"] = column([](const ContinuationPoint& p) { return p.index; });
    arrays["value"] = column([](const ContinuationPoint& p) { return p.parameter; });
    arrays["period"] = column([](const ContinuationPoint& p) { return p.orbit.period; });
    arrays["frequency"] = column([](const ContinuationPoint& p) { return 1.0 / p.orbit.period; });
    arrays["stable"] = column(
        [](const ContinuationPoint& p) { return p.orbit.floquet.stability == Stability::Stable; });
    arrays["unstable_count"] =
        column([](const ContinuationPoint& p) { return p.orbit.floquet.unstable_count; });
    arrays["max_modulus"] =
        column([](const ContinuationPoint& p) { return p.orbit.floquet.max_modulus; });
    arrays["trivial_multiplier_error"] =
        column([](const ContinuationPoint& p) { return p.orbit.floquet.trivial_error; });
    arrays["residual"] = column([](const ContinuationPoint& p) { return p.orbit.residual; });
    arrays["structural"] =
        column([](const ContinuationPoint& p) { return p.orbit.family_dimension; });
    arrays["iterations"] = column([](const ContinuationPoint& p) { return p.iterations; });
    arrays["step"] = column([](const ContinuationPoint& p) { return p.step; });
  }
  arrays["stability"] = stability;
  arrays["state0"] = matrix_array(states, dimension);
  // Multipliers by decreasing modulus per point (NaN where a point has fewer).
  py::array_t<std::complex<double>> mu(
      {static_cast<py::ssize_t>(n), static_cast<py::ssize_t>(count)});
  auto m = mu.mutable_unchecked<2>();
  for (std::size_t i = 0; i < n; ++i)
    for (int j = 0; j < count; ++j) {
      const auto& list = points[i].orbit.floquet.multipliers;
      m(i, j) = j < static_cast<int>(list.size())
                    ? list[j].value
                    : std::complex<double>(std::nan(""), std::nan(""));
    }
  arrays["multipliers"] = mu;
  add_described_columns(arrays, points, describer);
  py::list events;
  for (const auto& e : branch.events) events.append(event_result(e));
  py::dict rejected;
  rejected["corrector"] = branch.rejected.corrector;
  rejected["turn"] = branch.rejected.turn;
  rejected["multipliers"] = branch.rejected.multipliers;
  rejected["location"] = branch.rejected.location;
  py::dict fields;
  fields["parameter"] = branch.parameter_name;
  fields["points"] = with_fields(arrays);
  fields["events"] = events;
  fields["stop"] = to_string(branch.stop);
  fields["stop_reason"] = branch.stop_reason;
  fields["started"] = branch.started();
  fields["origin"] = branch.origin;
  fields["seconds"] = branch.seconds;
  fields["state_names"] = branch.state_names;
  fields["rejected"] = rejected;
  fields["stiffness"] = stiffness_result(branch.stiffness);
  return with_fields(fields);
}

py::object curve_point_result(const CurvePoint& p) {
  py::dict fields;
  fields["index"] = p.index;
  fields["first"] = p.first;
  fields["second"] = p.second;
  fields["period"] = p.period;
  fields["iterations"] = p.iterations;
  return with_fields(fields);
}

py::object curve_result(const BifurcationCurve& curve, const OrbitDescriber* describer) {
  using P = CurvePoint;
  const auto& points = curve.points;
  py::dict arrays;
  arrays["index"] = column_of(points, [](const P& p) { return p.index; });
  arrays["first"] = column_of(points, [](const P& p) { return p.first; });
  arrays["second"] = column_of(points, [](const P& p) { return p.second; });
  arrays["period"] = column_of(points, [](const P& p) { return p.period; });
  arrays["rotation"] = column_of(points, [](const P& p) { return p.rotation; });
  arrays["neutral_saddle"] = column_of(points, [](const P& p) { return p.neutral_saddle; });
  arrays["test"] = column_of(points, [](const P& p) { return p.test; });
  arrays["residual"] = column_of(points, [](const P& p) { return p.residual; });
  arrays["trivial_multiplier_error"] =
      column_of(points, [](const P& p) { return p.floquet.trivial_error; });
  arrays["uncertainty"] = column_of(points, [](const P& p) { return p.uncertainty; });
  arrays["iterations"] = column_of(points, [](const P& p) { return p.iterations; });
  arrays["step"] = column_of(points, [](const P& p) { return p.step; });
  std::vector<Eigen::VectorXd> states;
  for (const auto& p : points) states.push_back(p.state0);
  arrays["state0"] = matrix_array(states, static_cast<int>(curve.state_names.size()));
  arrays["multipliers"] = complex_rows(points, [](const P& p) { return values_of(p.floquet); });
  arrays["critical"] = complex_rows(points, [](const P& p) { return p.critical; });
  if (describer) add_described_columns(arrays, points, *describer);
  py::list events;
  for (const auto& e : curve.events) {
    py::dict f;
    f["type"] = e.type;
    f["description"] = e.description;
    f["first"] = e.first;
    f["second"] = e.second;
    f["uncertainty"] = e.uncertainty;
    f["located"] = e.located;
    f["crossing_symmetry"] = to_string(e.crossing_symmetry);
    f["note"] = e.note;
    f["after_point"] = e.after_point;
    events.append(with_fields(f));
  }
  py::dict fields;
  fields["kind"] = to_string(curve.kind);
  fields["first_name"] = curve.first_name;
  fields["second_name"] = curve.second_name;
  fields["points"] = with_fields(arrays);
  fields["events"] = events;
  fields["stop"] = to_string(curve.stop);
  fields["stop_reason"] = curve.stop_reason;
  fields["started"] = curve.started();
  fields["origin"] = curve.origin;
  fields["symmetry"] = to_string(curve.symmetry);
  fields["subspace"] = curve.subspace;
  fields["seconds"] = curve.seconds;
  fields["evaluations"] = curve.evaluations;
  fields["noise"] = curve.noise;
  fields["state_names"] = curve.state_names;
  return with_fields(fields);
}

py::object equilibrium_curve_point_result(const EquilibriumCurvePoint& p) {
  py::dict fields;
  fields["index"] = p.index;
  fields["first"] = p.first;
  fields["second"] = p.second;
  return with_fields(fields);
}

py::object equilibria_result(const EquilibriumBranch& branch) {
  using P = EquilibriumPoint;
  const auto& points = branch.points;
  auto complex_vector = [](const Eigen::VectorXcd& v) {
    return std::vector<std::complex<double>>(v.data(), v.data() + v.size());
  };
  py::dict arrays;
  arrays["index"] = column_of(points, [](const P& p) { return p.index; });
  arrays["value"] = column_of(points, [](const P& p) { return p.parameter; });
  arrays["unstable"] = column_of(points, [](const P& p) { return p.unstable; });
  arrays["residual"] = column_of(points, [](const P& p) { return p.residual; });
  arrays["step"] = column_of(points, [](const P& p) { return p.step; });
  arrays["iterations"] = column_of(points, [](const P& p) { return p.iterations; });
  std::vector<Eigen::VectorXd> states;
  for (const auto& p : points) states.push_back(p.state);
  arrays["state"] = matrix_array(states, static_cast<int>(branch.state_names.size()));
  arrays["eigenvalues"] =
      complex_rows(points, [&](const P& p) { return complex_vector(p.eigenvalues); });
  py::list events;
  for (const auto& e : branch.events) {
    py::dict f;
    f["type"] = to_string(e.type);
    f["value"] = e.parameter;
    f["uncertainty"] = e.uncertainty;
    f["located"] = e.located;
    f["state"] = vector_array(e.state);
    const auto eigenvalues = complex_vector(e.eigenvalues);
    py::array_t<std::complex<double>> ev(static_cast<py::ssize_t>(eigenvalues.size()));
    std::copy(eigenvalues.begin(), eigenvalues.end(), ev.mutable_data());
    f["eigenvalues"] = ev;
    f["note"] = e.note;
    f["after_point"] = e.after_point;
    if (e.hopf) {
      f["omega"] = e.hopf->omega;
      f["period"] = e.hopf->period;
      f["lyapunov"] = e.hopf->lyapunov ? py::cast(*e.hopf->lyapunov) : py::none();
    }
    events.append(with_fields(f));
  }
  py::dict fields;
  fields["parameter"] = branch.parameter_name;
  fields["points"] = with_fields(arrays);
  fields["events"] = events;
  fields["stop"] = to_string(branch.stop);
  fields["stop_reason"] = branch.stop_reason;
  fields["started"] = branch.started();
  fields["seconds"] = branch.seconds;
  fields["state_names"] = branch.state_names;
  return with_fields(fields);
}

py::object fit_result(const OdeSystem& model, const PreparedFit& fit,
                      const TrajectoryFitResult& result) {
  auto matrix = [](const Eigen::MatrixXd& m) {
    py::array_t<double> a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
    auto v = a.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (Eigen::Index j = 0; j < m.cols(); ++j) v(i, j) = m(i, j);
    return a;
  };
  py::dict column_rms, parameters;
  for (std::size_t k = 0; k < fit.recording.columns.size(); ++k)
    column_rms[py::str(fit.recording.columns[k])] =
        static_cast<Eigen::Index>(k) < result.column_rms.size() ? result.column_rms[k]
                                                                : std::nan("");
  const auto names = model.parameter_names();
  for (int i = 0; i < static_cast<int>(names.size()); ++i)
    parameters[py::str(names[i])] = model.parameter(result.fitted_parameters, i);
  py::dict fields;
  fields["names"] = fit.unknowns;
  fields["start"] = vector_array(result.start);
  fields["values"] = vector_array(result.values);
  fields["errors"] = vector_array(result.errors);
  fields["covariance"] = matrix(result.covariance);
  fields["correlation"] = matrix(result.correlation);
  fields["rss_start"] = result.rss_start;
  fields["rss"] = result.rss;
  fields["residuals"] = result.residuals;
  fields["sigma2"] = result.sigma2;
  fields["column_rms"] = column_rms;
  fields["rank"] = result.rank;
  fields["condition"] = result.condition;
  fields["evaluations"] = result.evaluations;
  fields["converged"] = result.converged;
  fields["interrupted"] = result.interrupted;
  fields["stop_reason"] = result.stop_reason;
  fields["seconds"] = result.seconds;
  fields["parameters"] = parameters;
  fields["model"] = fit.model_description;
  return with_fields(fields);
}

}  // namespace sympathy::python
