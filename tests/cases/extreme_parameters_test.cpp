// Orbits of the row setup far from the paper's tables: a near-discontinuous escapement, no and
// heavy platform damping, a nearly rigid, a nearly massless and a nearly immovable platform.
// Every one must converge at default settings with its accuracy figures; without hinge damping
// nothing balances the escapement's drive and the failure must say so.
#include <gtest/gtest.h>

#include <algorithm>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {
namespace {

struct Extreme {
  std::string start, key;
  double value;
};

void PrintTo(const Extreme& e, std::ostream* os) {
  *os << e.start << " " << e.key << "=" << e.value;
}

PeriodicOrbit row_orbit(const std::string& start, const std::vector<Assignment>& sets,
                        const OrbitOptions& options = {}) {
  const auto file = CaseFile::load(std::string(SYMPATHY_SOURCE_DIR) + "/cases/row2.toml");
  const MetronomeModel model(file.spec("table2", sets));
  const auto& s = file.start(start);
  return find_periodic_orbit(model, model.default_parameters(), file.initial_state(&s),
                             file.invariant_subspace(s, model), options);
}

// The command line's default preset: Adams with fixed point on the augmented system, rtol 5e-12,
// switched to BDF where the start is stiff.
OrbitOptions adams_switching() {
  OrbitOptions o;
  o.shooting.flow.method = Method::Adams;
  o.shooting.flow.nonlinear_solver = NonlinearSolver::FixedPoint;
  o.shooting.flow.sensitivities = Sensitivities::Augmented;
  o.shooting.flow.rtol = 5e-12;
  o.shooting.flow.atol = 5e-14;
  o.switch_when_stiff = true;
  return o;
}

class ExtremeParameters : public ::testing::TestWithParam<Extreme> {};

TEST_P(ExtremeParameters, OrbitConvergesWithItsAccuracy) {
  const auto& e = GetParam();
  const PeriodicOrbit orbit = row_orbit(e.start, {{e.key, e.value, "test"}});
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_LT(orbit.residual, 1e-9);
  EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
  // Anti-phase, the platform stays at rest (MODEL.md), so M, c and k cannot change the orbit:
  // its period is Table II's, 0.5814490514 s (computed at rtol 1e-13 by `sympathy bench`).
  if (e.start == "anti-phase" && e.key != "eps") {
    EXPECT_NEAR(orbit.period, 0.5814490514, 1e-8);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Row2, ExtremeParameters,
    ::testing::Values(Extreme{"in-phase", "eps", 0.005}, Extreme{"anti-phase", "eps", 0.005},
                      Extreme{"in-phase", "c", 0.0}, Extreme{"anti-phase", "c", 0.0},
                      Extreme{"in-phase", "c", 50.0}, Extreme{"anti-phase", "c", 50.0},
                      Extreme{"in-phase", "k", 1e4}, Extreme{"anti-phase", "k", 1e4},
                      Extreme{"in-phase", "M", 1e-3}, Extreme{"anti-phase", "M", 1e-3},
                      Extreme{"in-phase", "M", 100.0}, Extreme{"anti-phase", "M", 100.0}),
    [](const auto& info) {
      std::string s = info.param.start + "_" + info.param.key + "_" +
                      std::to_string(static_cast<int>(info.index));
      std::replace(s.begin(), s.end(), '-', '_');
      return s;
    });

// The stiffness indicator (core/stiffness.hpp) on the row setup: Table II's platform keeps Adams
// (indicator 0.52 measured: Adams' higher orders take fewer steps than BDF); a platform with
// k = 1e6 N/m and c = 5000 N s/m (its fast mode decays at 1.2e4 /s against a 0.58 s period)
// measured 9.2 uncapped (the measurement stops Adams at 4 times BDF's steps) and runs BDF, where
// forced Adams took 18 times the time (6.3 s against 0.35 s). The BDF orbit must carry the
// default's accuracy, and its multipliers agree with BDF's at rtol 1e-12 (the reference) to 1e-8;
// a branch measures once at its start and runs the chosen method.
TEST(ExtremeParameters, StiffPlatformRunsBdfByMeasurement) {
  const PeriodicOrbit paper = row_orbit("in-phase", {}, adams_switching());
  ASSERT_TRUE(paper.converged()) << paper.newton.reason;
  ASSERT_TRUE(paper.stiffness);
  EXPECT_EQ(paper.method, Method::Adams);
  EXPECT_LT(paper.stiffness->indicator, 1.0);

  const std::vector<Assignment> stiff{{"k", 1e6, "test"}, {"c", 5000.0, "test"}};
  const PeriodicOrbit orbit = row_orbit("in-phase", stiff, adams_switching());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  ASSERT_TRUE(orbit.stiffness);
  EXPECT_EQ(orbit.method, Method::BDF);
  EXPECT_TRUE(orbit.stiffness->capped);  // at least 4 times BDF's steps
  EXPECT_GT(orbit.stiffness->rate, 1e4);
  EXPECT_LT(orbit.residual, 1e-9);
  EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
  OrbitOptions reference;
  reference.shooting.flow.rtol = 1e-12;
  reference.shooting.flow.atol = 1e-14;
  const PeriodicOrbit exact = row_orbit("in-phase", stiff, reference);
  ASSERT_TRUE(exact.converged());
  EXPECT_NEAR(orbit.period, exact.period, 1e-9);
  ASSERT_EQ(orbit.floquet.multipliers.size(), exact.floquet.multipliers.size());
  for (std::size_t i = 0; i < exact.floquet.multipliers.size(); ++i)
    EXPECT_LT(std::abs(orbit.floquet.multipliers[i].value - exact.floquet.multipliers[i].value),
              1e-8)
        << i;

  const auto file = CaseFile::load(std::string(SYMPATHY_SOURCE_DIR) + "/cases/row2.toml");
  const MetronomeModel model(file.spec("table2", stiff));
  ContinuationOptions co;
  co.orbit = adams_switching();
  co.lower = 1e6;
  co.upper = 1.02e6;
  co.max_points = 3;
  Continuation continuation(model, model.parameter_index("k"), co);
  const Branch branch = continuation.run(orbit, +1);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  ASSERT_TRUE(branch.stiffness);
  EXPECT_TRUE(branch.stiffness->capped);
  EXPECT_EQ(branch.options.orbit.shooting.flow.method, Method::BDF);
  EXPECT_EQ(branch.options.orbit.shooting.flow.sensitivities, Sensitivities::ForwardModule);
  EXPECT_GE(branch.points.size(), 2u);
  for (const auto& p : branch.points) EXPECT_LT(p.orbit.floquet.trivial_error, 1e-8);

  // The choice is each run's, recorded in its branch: one object run from the stiff orbit runs
  // BDF, then from Table II's orbit Adams again (the first run's choice used to stay for every
  // later run of the object), then from the stiff one BDF again.
  co.lower = 1.0;
  Continuation both(model, model.parameter_index("k"), co);
  const Branch stiff_first = both.run(orbit, +1);
  const Branch paper_branch = both.run(paper, +1);
  const Branch stiff_again = both.run(orbit, -1);
  for (const Branch* b : {&stiff_first, &paper_branch, &stiff_again})
    ASSERT_TRUE(b->started() && b->stiffness) << b->stop_reason;
  EXPECT_EQ(stiff_first.options.orbit.shooting.flow.method, Method::BDF);
  EXPECT_EQ(paper_branch.options.orbit.shooting.flow.method, Method::Adams);
  EXPECT_LT(paper_branch.stiffness->indicator, 1.0);
  EXPECT_EQ(stiff_again.options.orbit.shooting.flow.method, Method::BDF);
}

// d = 0: the escapement feeds energy each swing and the hinges take none out, so the swing
// grows (a 600 s simulation: th1 reaches 2.5 rad by 60 s, then the pendula go over the top) and
// there is no periodic orbit. Newton must fail and say why.
TEST(ExtremeParameters, NoHingeDampingFailsWithADiagnosis) {
  for (const std::string start : {"in-phase", "anti-phase"}) {
    const PeriodicOrbit orbit = row_orbit(start, {{"d", 0.0, "test"}});
    EXPECT_FALSE(orbit.converged()) << start;
    EXPECT_NE(orbit.newton.reason.find("had not settled on a periodic orbit"), std::string::npos)
        << orbit.newton.reason;
  }
}

}  // namespace
}  // namespace sympathy
