// Periodic orbits of the paper's setups at default settings: the stability verdicts of
// Secs. III and IV, the cross setup's decoupling (MODEL.md), and the monodromy itself.
#include <gtest/gtest.h>

#include <algorithm>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/continuation/shooting.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

using testing::case_path;
using testing::load_spec;
using testing::random_state;

struct Found {
  std::unique_ptr<MetronomeModel> model;
  PeriodicOrbit orbit;
};

Found find(const std::string& name, const std::string& params, const std::string& start,
           const std::vector<Assignment>& sets = {}, const OrbitOptions& options = {}) {
  const auto file = CaseFile::load(case_path(name));
  Found f;
  f.model = std::make_unique<MetronomeModel>(file.spec(params, sets));
  const auto& s = file.start(start);
  f.orbit = find_periodic_orbit(*f.model, f.model->default_parameters(), file.initial_state(&s),
                                file.invariant_subspace(s, *f.model), options);
  return f;
}

// Multipliers other than the trivial and structural ones, by decreasing modulus.
std::vector<std::complex<double>> others(const FloquetAnalysis& a) {
  std::vector<std::complex<double>> v;
  for (const auto& m : a.multipliers)
    if (!m.trivial && !m.structural) v.push_back(m.value);
  return v;
}

struct Verdict {
  std::string name, params, start;
  Stability expected;
};

void PrintTo(const Verdict& v, std::ostream* os) {
  *os << v.name << " " << v.params << " " << v.start;
}

class PaperVerdicts : public ::testing::TestWithParam<Verdict> {};

// Row setup (Sec. III): Table II in-phase stable and anti-phase unstable, Table III both
// stable. Cross with virtual spring (Sec. IV C): Table IV in-in stable and anti-anti unstable,
// Table V anti-anti unstable. Every orbit at default settings: Newton converged, trivial
// multiplier within 1e-8 of 1.
TEST_P(PaperVerdicts, StabilityAndAccuracy) {
  const auto& v = GetParam();
  const Found f = find(v.name, v.params, v.start);
  ASSERT_TRUE(f.orbit.converged()) << f.orbit.newton.reason;
  EXPECT_EQ(f.orbit.floquet.stability, v.expected);
  EXPECT_LT(f.orbit.floquet.trivial_error, 1e-8);
  EXPECT_LT(f.orbit.residual, 1e-9);
  // The multipliers sit near the unit circle (0.96 to 1.13 on these cases).
  for (const auto& m : others(f.orbit.floquet)) EXPECT_GT(std::abs(m), 0.5);
}

INSTANTIATE_TEST_SUITE_P(
    Paper, PaperVerdicts,
    ::testing::Values(Verdict{"row2", "table2", "in-phase", Stability::Stable},
                      Verdict{"row2", "table2", "anti-phase", Stability::Unstable},
                      Verdict{"row2", "table3", "in-phase", Stability::Stable},
                      Verdict{"row2", "table3", "anti-phase", Stability::Stable},
                      Verdict{"cross4_spring", "table4", "in-in", Stability::Stable},
                      Verdict{"cross4_spring", "table4", "anti-anti", Stability::Unstable},
                      Verdict{"cross4_spring", "table5", "anti-anti", Stability::Unstable}),
    [](const auto& info) {
      std::string s = info.param.name + "_" + info.param.params + "_" + info.param.start;
      std::replace(s.begin(), s.end(), '-', '_');
      return s;
    });

// The anti-phase orbit is unstable in the full space, yet found: it lies in its start's
// invariant subspace, where the platform stays exactly still.
TEST(Orbits, AntiPhaseOrbitLiesInItsSubspace) {
  const Found f = find("row2", "table2", "anti-phase");
  ASSERT_TRUE(f.orbit.converged());
  const auto& z = f.orbit.state0;  // x, th1, th2, vx, vth1, vth2
  EXPECT_EQ(z[0], 0.0);
  EXPECT_EQ(z[3], 0.0);
  EXPECT_EQ(z[2], -z[1]);
  EXPECT_EQ(z[5], -z[4]);
  EXPECT_GT(std::abs(z[1]) + std::abs(z[4]), 0.1);
}

// MODEL.md: the isotropic cross platform splits into two row-like systems, each a pair on a
// platform of mass Mt (so M_row = M + 2 (mp + mb)). The cross in-in orbit then has two
// multipliers at 1 (trivial, and the free phase between the pairs: structural), and each other
// multiplier twice: those of the row-like system's in-phase orbit, to 1e-8.
TEST(Orbits, CrossSetupDecouplesIntoRowLikeSystems) {
  const Found cross = find("cross4", "table4", "in-in");
  ASSERT_TRUE(cross.orbit.converged()) << cross.orbit.newton.reason;
  EXPECT_EQ(cross.orbit.family_dimension, 1);
  int at_one = 0;
  for (const auto& m : cross.orbit.floquet.multipliers)
    if (std::abs(m.value - 1.0) < 1e-8) ++at_one;
  EXPECT_EQ(at_one, 2);

  // spec() returns a ModelSpec by value: keep it, not a reference into it.
  const ModelSpec row_spec = CaseFile::load(case_path("row2")).spec();
  const auto& table1 = row_spec.metronomes[0].values;
  const double pair_mass = 2.0 * (table1.at("mp") + table1.at("mb"));
  const Found row =
      find("row2", "", "in-phase",
           {{"M", 0.6366 + pair_mass, "test"}, {"c", 0.0285, "test"}, {"k", 24.3431, "test"}});
  ASSERT_TRUE(row.orbit.converged());
  EXPECT_NEAR(cross.orbit.period, row.orbit.period, 1e-9);
  std::vector<std::complex<double>> expected;
  for (const auto& m : others(row.orbit.floquet)) expected.insert(expected.end(), 2, m);
  auto actual = others(cross.orbit.floquet);
  ASSERT_EQ(actual.size(), expected.size());
  // Match each expected multiplier to a distinct computed one.
  for (const auto& e : expected) {
    auto it = std::min_element(actual.begin(), actual.end(),
                               [&](auto a, auto b) { return std::abs(a - e) < std::abs(b - e); });
    EXPECT_LT(std::abs(*it - e), 1e-8) << e;
    actual.erase(it);
  }
}

// The monodromy from CVODES sensitivities against central differences of the flow over one
// period of the row setup's in-phase orbit. The integrated map carries noise of about 100 rtol,
// which a difference divides by its step: at rtol 1e-13 and step 1e-5 noise and truncation are
// both about 1e-7 of |M| (measured 1.3e-7; the sensitivities themselves agree with rtol 1e-12
// to 1e-10 of |M|).
TEST(Orbits, MonodromyMatchesFiniteDifferences) {
  const Found f = find("row2", "table2", "in-phase");
  ASSERT_TRUE(f.orbit.converged());
  FlowOptions o;
  o.rtol = 1e-13;
  o.atol = 1e-15;
  Flow flow(*f.model, o);
  const auto& z = f.orbit.state0;
  const double T = f.orbit.period;
  const ParameterValues& p = f.orbit.parameters;
  const Eigen::MatrixXd monodromy = flow.advance_with_sensitivities(z, p, 0.0, T).transition;
  const int n = static_cast<int>(z.size());
  Eigen::MatrixXd fd(n, n);
  for (int j = 0; j < n; ++j) {
    const double h = 1e-5;
    Eigen::VectorXd zp = z, zm = z;
    zp[j] += h;
    zm[j] -= h;
    fd.col(j) = (flow.advance(zp, p, 0.0, T) - flow.advance(zm, p, 0.0, T)) / (2 * h);
  }
  for (int j = 0; j < n; ++j)
    EXPECT_LT((monodromy.col(j) - fd.col(j)).norm(), 5e-7 * monodromy.norm()) << "column " << j;
}

// A plain residual (ShootingProblem::residual, tightened) is as accurate as that of a run with
// sensitivities at the same point, so that quasi-Newton steps on plain runs can finish a
// continuation point that one run with sensitivities then accepts. Reference: a run at rtol
// 1e-13. Measured at the default rtol 1e-11: plain 2.5e-10 and 4.9e-10, with sensitivities 1.5e-9
// and 6.1e-10 (in-phase, anti-phase); a plain run at the flow's own settings is off by 3.7e-9 and
// 4.1e-8.
TEST(Orbits, PlainResidualAsAccurateAsTheSensitivityRuns) {
  // From where the whole 60 s transient ends, as when the bounds below were set: two integrations
  // of one period differ by an amount that depends on where on the orbit they start (from the
  // point Newton tried at 12 s lands on, OrbitOptions::early_newton_below: plain 1.07e-9).
  OrbitOptions whole_transient;
  whole_transient.early_newton_below = 0.0;
  for (const char* start : {"in-phase", "anti-phase"}) {
    const Found f = find("row2", "table2", start, {}, whole_transient);
    ASSERT_TRUE(f.orbit.converged());
    const ParameterValues& p = f.orbit.parameters;
    ShootingProblem problem(*f.model, ShootingOptions{});
    const PhaseSection section = problem.section_through(f.orbit.state0, p);
    const Eigen::VectorXd x = problem.unknowns_from(f.orbit.state0, p, f.orbit.period);
    ShootingOptions tight;
    tight.flow.rtol = 1e-13;
    tight.flow.atol = 1e-15;
    ShootingProblem reference(*f.model, tight);
    const Eigen::VectorXd exact = reference.evaluate(x, p, section, false).residual;
    const double plain = (problem.residual(x, p, section) - exact).cwiseAbs().maxCoeff();
    const double with_derivatives =
        (problem.evaluate(x, p, section, true).residual - exact).cwiseAbs().maxCoeff();
    EXPECT_LT(plain, 1e-9) << start;
    EXPECT_LT(with_derivatives, 3e-9) << start;
    EXPECT_LT(plain, 2.0 * with_derivatives + 1e-10) << start;
    // A coarse plain run (a thousand times looser) is used only where the residual is expected
    // above a thousand corrector tolerances (1e-6 here, CorrectorOptions::coarse_above): its
    // error must stay well below that, a fifth (measured 1.4e-7 and 1.6e-7 from the points where
    // the default preset's transients end, 3.9e-8 and 2.8e-8 from BDF's at rtol 1e-11: the
    // error depends on where on the orbit the period starts).
    const double coarse = (problem.residual(x, p, section, true) - exact).cwiseAbs().maxCoeff();
    EXPECT_LT(coarse, 2e-7) << start;
  }
}

// The same orbit computed with 1, 3, 5, 10 and 50 shooting segments: the same multipliers to
// 1e-8 (multiple shooting through the periodic Schur decomposition of the segments).
TEST(Orbits, SegmentCountGivesSameMultipliers) {
  const Found f = find("row2", "table2", "in-phase");
  ASSERT_TRUE(f.orbit.converged());
  const auto reference = f.orbit.floquet.multipliers;
  for (int m : {1, 3, 5, 10, 50}) {
    OrbitOptions o;
    o.shooting.segments = m;
    const auto orbit =
        solve_periodic_orbit(*f.model, f.orbit.parameters, f.orbit.state0, f.orbit.period, {}, o);
    ASSERT_TRUE(orbit.converged()) << m << ": " << orbit.newton.reason;
    ASSERT_EQ(orbit.floquet.multipliers.size(), reference.size());
    for (std::size_t k = 0; k < reference.size(); ++k)
      EXPECT_LT(std::abs(orbit.floquet.multipliers[k].value - reference[k].value), 1e-8)
          << m << " segments, multiplier " << k;
    EXPECT_NEAR(orbit.period, f.orbit.period, 1e-10) << m;
  }
}

// The cross setup's in-anti start lies on no periodic orbit: its pairs run at the different
// frequencies of the in-phase and anti-phase motions, uncoupled. Newton says so; no crash.
TEST(Orbits, QuasiPeriodicStartIsReportedNotConverged) {
  const Found f = find("cross4", "table4", "in-anti");
  EXPECT_FALSE(f.orbit.converged());
  EXPECT_FALSE(f.orbit.newton.reason.empty());
}

}  // namespace
}  // namespace sympathy
