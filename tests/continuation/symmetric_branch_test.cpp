// Branches of N identical metronomes in phase computed in the symmetry reduction
// (continuation/symmetry_reduction.hpp) against the same branches on the whole state, and the
// lifting of what the reduction computes.
#include <gtest/gtest.h>

#include <cmath>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_describer.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/continuation/symmetry_reduction.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

// Four identical metronomes, in-phase k-branch from Table II's (scaled) 29.49 to 36 N/m computed
// in the reduction (the platform and two metronomes): every point it hands out is whole (10
// states, 10 multipliers, the whole state names), and is the orbit that Newton on the whole state
// finds at its parameter values: state and period to 1e-8, every multiplier to 1e-8 (their own
// accuracy at rtol 1e-11); its description that of the whole orbit.
TEST(SymmetricBranch, ReducedBranchPointsAreWholeOrbits) {
  const CaseFile file = CaseFile::load(testing::case_path("row/row4"));
  const MetronomeModel model(file.spec());
  const BranchProblem problem = testing::branch_problem(file, model, "in-phase", "k", 36.0);
  const MetronomeDescriber describer(model);
  int handed_out = 0;
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint& p) {
    EXPECT_EQ(p.orbit.state0.size(), 10);
    EXPECT_EQ(p.orbit.floquet.multipliers.size(), 10u);
    EXPECT_EQ(p.unknowns.size(), 11);
    ++handed_out;
  };
  const Branch branch =
      continue_branch(model, problem, ContinuationOptions{}, callbacks, &describer);
  ASSERT_TRUE(branch.started());
  EXPECT_EQ(branch.stop, StopReason::ParameterBound);
  EXPECT_EQ(handed_out, static_cast<int>(branch.points.size()));
  EXPECT_EQ(branch.state_names, model.state_names());
  ASSERT_GE(branch.points.size(), 3u);
  OrbitOptions whole;
  whole.use_symmetry = false;
  for (std::size_t i = 0; i < branch.points.size(); i += 2) {
    const PeriodicOrbit& a = branch.points[i].orbit;
    EXPECT_FALSE(a.reduction.empty());
    const PeriodicOrbit b =
        solve_periodic_orbit(model, a.parameters, a.state0, a.period, problem.subspace, whole);
    ASSERT_TRUE(b.converged()) << i;
    EXPECT_NEAR(a.period, b.period, 1e-9) << i;
    EXPECT_LT((a.state0 - b.state0).cwiseAbs().maxCoeff(), 1e-8) << i;
    ASSERT_EQ(a.floquet.multipliers.size(), b.floquet.multipliers.size());
    // Both by decreasing modulus; repeated ones in any order: moduli and kinds one by one.
    for (std::size_t k = 0; k < b.floquet.multipliers.size(); ++k) {
      EXPECT_NEAR(a.floquet.multipliers[k].modulus(), b.floquet.multipliers[k].modulus(), 1e-8)
          << i << ", " << k;
      EXPECT_EQ(a.floquet.multipliers[k].symmetry, b.floquet.multipliers[k].symmetry)
          << i << ", " << k;
    }
    const std::vector<double> expected = describer.describe(b);
    ASSERT_EQ(branch.points[i].description.size(), expected.size());
    for (std::size_t k = 0; k < expected.size(); ++k) {
      if (std::isfinite(expected[k])) {
        EXPECT_NEAR(branch.points[i].description[k], expected[k], 1e-6) << i << ", " << k;
      }
    }
  }
}

// A breaking crossing of the block is one in each of its N - 1 copies: multiplicity and note
// say so; a keeping one stays single.
TEST(SymmetricBranch, LiftedEventsCountTheirCopies) {
  const CaseFile file = CaseFile::load(testing::case_path("row/row8"));
  const MetronomeModel model(file.spec());
  const InvariantSubspace subspace = file.invariant_subspace(file.start("in-phase"), model);
  const auto r = symmetry_reduction(model, model.default_parameters(), subspace);
  ASSERT_TRUE(r.has_value());
  EXPECT_EQ(r->copies, 7);
  EXPECT_EQ(r->system->dimension(), 6);
  Bifurcation breaking;
  breaking.type = BifurcationType::NeimarkSacker;
  breaking.symmetry = SymmetryKind::Breaking;
  breaking.state0 = Eigen::VectorXd::Zero(6);
  const Bifurcation lifted = lift(breaking, *r, FloquetOptions{});
  EXPECT_EQ(lifted.multiplicity, 7);
  EXPECT_EQ(lifted.note, "7 complex pairs cross together");
  EXPECT_EQ(lifted.state0.size(), 18);
  Bifurcation keeping = breaking;
  keeping.symmetry = SymmetryKind::Keeping;
  keeping.note = "not trusted: something";
  const Bifurcation same = lift(keeping, *r, FloquetOptions{});
  EXPECT_EQ(same.multiplicity, 1);
  EXPECT_EQ(same.note, "not trusted: something");
}

}  // namespace
}  // namespace sympathy
