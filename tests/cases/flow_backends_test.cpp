// The flow's integrators on the row setup's anti-phase orbit (cases/row2.toml, Table II): the
// monodromy and the parameter column of one period from the same state, and the multipliers of the
// orbit each finds by Newton, against the CVODES forward-sensitivity module's; and the
// turning-point caps at work on every backend (the escapement pulse, NUMERICS.md).
#include <gtest/gtest.h>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/assignment.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

using testing::case_path;

struct Backend {
  std::string name;
  FlowOptions flow;
  double scale =
      1.0;  // of the tolerances below (ERKStep's Verner 6(5): measured ~10x less accurate)
};

// At rtol 1e-11 (the library's shooting default), atol 1e-13.
std::vector<Backend> backends() {
  std::vector<Backend> b;
  auto add = [&](const std::string& name, Method m, Sensitivities s,
                 ExplicitTable t = ExplicitTable::DormandPrince, double scale = 1.0) {
    FlowOptions o = OrbitOptions{}.shooting.flow;
    o.method = m;
    o.nonlinear_solver = m == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
    o.sensitivities = s;
    o.explicit_table = t;
    b.push_back({name, o, scale});
  };
  add("augmented, Adams", Method::Adams, Sensitivities::Augmented);
  add("augmented, BDF", Method::BDF, Sensitivities::Augmented);
  add("ERK, Dormand-Prince", Method::ERK, Sensitivities::Augmented);
  add("ERK, Verner", Method::ERK, Sensitivities::Augmented, ExplicitTable::Verner, 5.0);
  return b;
}

// Largest distance between two sets of multipliers, paired by least total squared distance.
double multiplier_distance(const FloquetAnalysis& a, const FloquetAnalysis& b) {
  const int n = static_cast<int>(a.multipliers.size());
  if (n != static_cast<int>(b.multipliers.size())) return INFINITY;
  Eigen::MatrixXd cost(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      cost(i, j) = std::norm(a.multipliers[i].value - b.multipliers[j].value);
  const std::vector<int> pair = least_cost_assignment(cost);
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    worst = std::max(worst, std::abs(a.multipliers[i].value - b.multipliers[pair[i]].value));
  return worst;
}

class RowAntiPhase : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const auto file = CaseFile::load(case_path("row2"));
    model_ = new MetronomeModel(file.spec("table2"));
    const auto& start = file.start("anti-phase");
    subspace_ = new InvariantSubspace(file.invariant_subspace(start, *model_));
    orbit_ = new PeriodicOrbit(find_periodic_orbit(*model_, model_->default_parameters(),
                                                   file.initial_state(&start), *subspace_,
                                                   OrbitOptions{}));
  }
  static void TearDownTestSuite() {
    delete orbit_;
    delete subspace_;
    delete model_;
  }
  static MetronomeModel* model_;
  static InvariantSubspace* subspace_;
  static PeriodicOrbit* orbit_;
};
MetronomeModel* RowAntiPhase::model_ = nullptr;
InvariantSubspace* RowAntiPhase::subspace_ = nullptr;
PeriodicOrbit* RowAntiPhase::orbit_ = nullptr;

// One period from the same state with the transition matrix and dz/dd: every backend's against
// the forward module's (BDF, rtol 1e-11), within 1e-8 relative (measured at most 2.5e-9; Verner
// 3.7e-8, bound 5e-8); the steep-zone caps at work on each (steep_roots: 64 band changes a period
// on every backend).
TEST_F(RowAntiPhase, MonodromyAndParameterColumnAgreeBetweenBackends) {
  ASSERT_TRUE(orbit_->converged());
  // The pendulum damping d: dz/dk is zero on this orbit (the platform stands still, x = 0).
  const std::vector<int> parameters{model_->parameter_index("d")};
  Flow forward(*model_, OrbitOptions{}.shooting.flow);
  const auto reference = forward.advance_with_sensitivities(orbit_->state0, orbit_->parameters, 0.0,
                                                            orbit_->period, true, parameters);
  for (const auto& b : backends()) {
    Flow flow(*model_, b.flow);
    const auto r = flow.advance_with_sensitivities(orbit_->state0, orbit_->parameters, 0.0,
                                                   orbit_->period, true, parameters);
    const double bound = 1e-8 * b.scale;
    EXPECT_LT((r.state - reference.state).norm(), bound * reference.state.norm()) << b.name;
    EXPECT_LT((r.transition - reference.transition).norm(), bound * reference.transition.norm())
        << b.name;
    EXPECT_LT((r.parameter_sensitivities - reference.parameter_sensitivities).norm(),
              bound * reference.parameter_sensitivities.norm())
        << b.name;
    EXPECT_GT(flow.statistics().steep_roots, 0) << b.name;
    EXPECT_GT(flow.statistics().variational_evaluations, 0) << b.name;
  }
}

// Newton on each backend from the forward module's orbit moved by 1e-3: the same orbit and the
// same multipliers. At rtol 1e-11 the forward module's multipliers are good to about 4e-9
// (NUMERICS.md); every backend's agree with them within 1e-8 (measured at most 4.5e-9; Verner
// 1.7e-8, bound 5e-8) and the period within 1e-10 relative (measured 3e-11; Verner 4.2e-9, bound
// 1e-8); every trivial multiplier within 1e-8 of 1 (measured 5e-9).
TEST_F(RowAntiPhase, MultipliersAgreeWithTheForwardModule) {
  ASSERT_TRUE(orbit_->converged());
  const Eigen::VectorXd guess = subspace_->project(orbit_->state0 * (1.0 + 1e-3));
  const double period = orbit_->period * (1.0 + 1e-3);
  for (const auto& b : backends()) {
    OrbitOptions o;
    o.shooting.flow = b.flow;
    const PeriodicOrbit orbit =
        solve_periodic_orbit(*model_, orbit_->parameters, guess, period, *subspace_, o);
    ASSERT_TRUE(orbit.converged()) << b.name << ": " << orbit.newton.reason;
    EXPECT_NEAR(orbit.period, orbit_->period,
                (b.scale > 1.0 ? 2e-9 * b.scale : 1e-10) * orbit_->period)
        << b.name;
    EXPECT_LT(multiplier_distance(orbit.floquet, orbit_->floquet), 1e-8 * b.scale) << b.name;
    EXPECT_LT(orbit.floquet.trivial_error, 1e-8) << b.name;
    EXPECT_EQ(orbit.floquet.stability, orbit_->floquet.stability) << b.name;
    EXPECT_GT(orbit.flow.steep_roots, 0) << b.name;
  }
}

}  // namespace
}  // namespace sympathy
