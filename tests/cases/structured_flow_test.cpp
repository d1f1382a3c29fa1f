// The flow's structured linear solver (LinearSolver::Structured) on the metronome model against
// the dense solver: states, transition matrices, orbits.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

using testing::case_path;
using testing::load_spec;
using testing::random_state;

FlowOptions options(LinearSolver solver) {
  FlowOptions o;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  o.linear_solver = solver;
  return o;
}

// Expected: the same integration with the dense solver. Both solve the Newton systems to
// rounding, so they differ by the integration's own error control only (~rtol).
void expect_same_flow(const MetronomeModel& model, const Eigen::VectorXd& z0, double t1) {
  Flow dense(model, options(LinearSolver::Dense));
  Flow structured(model, options(LinearSolver::Structured));
  const ParameterValues p = model.default_parameters();
  const FlowDerivatives a = dense.advance_with_sensitivities(z0, p, 0.0, t1);
  const FlowDerivatives b = structured.advance_with_sensitivities(z0, p, 0.0, t1);
  EXPECT_LE((a.state - b.state).cwiseAbs().maxCoeff(), 1e-8 * a.state.cwiseAbs().maxCoeff());
  EXPECT_LE((a.transition - b.transition).cwiseAbs().maxCoeff(),
            1e-8 * a.transition.cwiseAbs().maxCoeff());
  // CVODES decides the setups and Jacobian evaluations alike for both.
  EXPECT_GT(structured.statistics().linear_setups, 0);
  EXPECT_GT(structured.statistics().jacobian_evaluations, 0);
  EXPECT_NEAR(static_cast<double>(structured.statistics().steps),
              static_cast<double>(dense.statistics().steps), 0.05 * dense.statistics().steps);
}

TEST(StructuredFlow, SameStateAndTransitionAsDenseOnRow2) {
  const auto file = CaseFile::load(case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  const auto& start = file.start("anti-phase");
  expect_same_flow(model, file.initial_state(&start), 0.6);
}

TEST(StructuredFlow, SameStateAndTransitionAsDenseOnMany16) {
  const auto file = CaseFile::load(case_path("many/many16"));
  const MetronomeModel model(file.spec(file.default_parameter_set()));
  const auto& start = file.start("in-phase");
  expect_same_flow(model, file.initial_state(&start), 0.15);
}

// The impulsive escapement: no sensitivities (not differentiable), the dense solver on CVODES's
// difference quotients, the structured one on the piecewise Jacobian; restarts at switchings.
TEST(StructuredFlow, SameStateAsDenseWithImpulsiveEscapement) {
  const auto file = CaseFile::load(case_path("cross4_spring"));
  ModelSpec spec = file.spec("");
  spec.escapement = Escapement::Impulsive;
  const MetronomeModel model(spec);
  const auto& start = file.start("in-in");
  const Eigen::VectorXd z0 = file.initial_state(&start);
  Flow dense(model, options(LinearSolver::Dense));
  Flow structured(model, options(LinearSolver::Structured));
  const ParameterValues p = model.default_parameters();
  const Eigen::VectorXd a = dense.advance(z0, p, 0.0, 1.5);
  const Eigen::VectorXd b = structured.advance(z0, p, 0.0, 1.5);
  EXPECT_GT(structured.statistics().switchings, 0);
  EXPECT_LE((a - b).cwiseAbs().maxCoeff(), 1e-7 * a.cwiseAbs().maxCoeff());
}

// The automatic choice: structured above three metronomes (where bench section (e) measured it
// faster), dense at two and three, and dense with difference quotients; an explicit choice stands.
TEST(StructuredFlow, AutomaticChoiceOfTheLinearSolver) {
  auto resolved = [](const std::string& name, const std::string& params, FlowOptions o) {
    return resolved_linear_solver(MetronomeModel(load_spec(name, params)), o);
  };
  const FlowOptions automatic;
  EXPECT_EQ(automatic.linear_solver, LinearSolver::Automatic);
  EXPECT_EQ(resolved("row2", "table2", automatic), LinearSolver::Dense);
  EXPECT_EQ(resolved("cross4", "table4", automatic), LinearSolver::Structured);
  EXPECT_EQ(resolved("cross4_spring", "table4", automatic), LinearSolver::Structured);
  EXPECT_EQ(resolved("many/many16", "", automatic), LinearSolver::Structured);
  ModelSpec three = load_spec("cross4", "table4");
  three.metronomes.pop_back();
  EXPECT_EQ(resolved_linear_solver(MetronomeModel(three), automatic), LinearSolver::Dense);
  FlowOptions quotients;
  quotients.derivatives = Derivatives::DifferenceQuotients;
  EXPECT_EQ(resolved("many/many16", "", quotients), LinearSolver::Dense);
  EXPECT_EQ(resolved("many/many16", "", options(LinearSolver::KLU)), LinearSolver::KLU);
  EXPECT_EQ(resolved("row2", "table2", options(LinearSolver::Structured)),
            LinearSolver::Structured);
}

// Expected: the same orbit found with the dense solver (multipliers matched nearest first).
TEST(StructuredFlow, OrbitMultipliersAgreeWithDense) {
  const auto file = CaseFile::load(case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  const auto& start = file.start("anti-phase");
  std::vector<std::vector<std::complex<double>>> multipliers;
  std::vector<double> periods;
  for (auto solver : {LinearSolver::Dense, LinearSolver::Structured}) {
    OrbitOptions o;
    o.shooting.flow.linear_solver = solver;
    o.transient_flow.linear_solver = solver;
    const PeriodicOrbit orbit =
        find_periodic_orbit(model, model.default_parameters(), file.initial_state(&start),
                            file.invariant_subspace(start, model), o);
    ASSERT_TRUE(orbit.converged()) << to_string(solver) << ": " << orbit.newton.reason;
    std::vector<std::complex<double>> m;
    for (const auto& mu : orbit.floquet.multipliers) m.push_back(mu.value);
    multipliers.push_back(m);
    periods.push_back(orbit.period);
  }
  EXPECT_NEAR(periods[0], periods[1], 1e-9);
  auto a = multipliers[0], b = multipliers[1];
  ASSERT_EQ(a.size(), b.size());
  for (const auto& mu : a) {
    auto nearest = std::min_element(
        b.begin(), b.end(), [&](auto p, auto q) { return std::abs(p - mu) < std::abs(q - mu); });
    EXPECT_LT(std::abs(*nearest - mu), 1e-8) << mu;
    b.erase(nearest);
  }
}

}  // namespace
}  // namespace sympathy
