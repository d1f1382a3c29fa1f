// The engine's results as Python values: NumPy arrays for numbers along a branch or a time series,
// complex arrays for multipliers, and plain objects (types.SimpleNamespace) whose attributes are
// the fields of the C++ results, named as the JSON writers name them (branch_output.hpp).
#pragma once

#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <Eigen/Dense>

#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/equilibrium_curve.hpp"
#include "sympathy/continuation/orbit_describer.hpp"
#include "sympathy/core/trajectory_fit.hpp"

namespace sympathy::python {

namespace py = pybind11;

py::array vector_array(const Eigen::VectorXd& v);
// Rows of equal length as a 2-D array (rows x columns).
py::array matrix_array(const std::vector<Eigen::VectorXd>& rows, int columns);
py::array multiplier_array(const FloquetAnalysis& floquet);

// period, frequency, state0, state_names, multipliers, moduli, kinds, symmetry, stable, stability,
// unstable_count, max_modulus, residual, trivial_multiplier_error, family_dimension, converged,
// newton (iterations, residuals, reason), segments, reduction, parameters, seconds, and the
// describer's groups (amplitudes, phase_differences: dicts by label).
py::object orbit_result(const OdeSystem& system, const PeriodicOrbit& orbit,
                        const OrbitDescriber& describer);
// A point as the progress callback gets it: index, value, period, stability, max_modulus, step,
// iterations.
py::object point_result(const ContinuationPoint& p);
// type, name, value, uncertainty, bracket, period, multipliers, crossing, multiplicity, located,
// location, symmetry, trusted, note, state0, after_point.
py::object event_result(const Bifurcation& e);
// parameter, points (arrays along the branch: index, value, period, frequency, stable, stability,
// unstable_count, max_modulus, trivial_multiplier_error, residual, structural, iterations, step,
// state0, multipliers, and the describer's groups), events, stop, stop_reason, origin, seconds,
// state_names, rejected.
py::object branch_result(const Branch& branch, const OrbitDescriber& describer);
// A curve point as the progress callback gets it: index, first, second, period, iterations.
py::object curve_point_result(const CurvePoint& p);
// kind, first_name, second_name, points (arrays along the curve: index, first, second, period,
// rotation, neutral_saddle, test, residual, trivial_multiplier_error, uncertainty, iterations,
// step, state0, multipliers, critical), events (type, description, first, second, uncertainty,
// located, crossing_symmetry, note, after_point), stop, stop_reason, origin, symmetry, subspace,
// seconds, evaluations, state_names.
py::object curve_result(const BifurcationCurve& curve, const OrbitDescriber* describer = nullptr);
// parameter, points (arrays along the branch: index, value, state, eigenvalues, unstable,
// residual, step, iterations), events (type, value, uncertainty, located, state, eigenvalues,
// note, after_point, and for HB omega, period, lyapunov), stop, stop_reason, seconds, state_names.
py::object equilibria_result(const EquilibriumBranch& branch);
// A point of a curve of equilibria, for progress: index, first, second.
py::object equilibrium_curve_point_result(const EquilibriumCurvePoint& p);
// names (the unknowns: "d", "th1(0)"), start, values, errors, covariance, correlation, rss_start,
// rss, residuals, sigma2, column_rms (by recorded column), rank, condition, evaluations,
// converged, stop_reason, seconds, parameters (every parameter of the model at the fitted values).
py::object fit_result(const OdeSystem& model, const PreparedFit& fit,
                      const TrajectoryFitResult& result);

}  // namespace sympathy::python
