// Multipliers labelled by the symmetry their perturbations keep or break (label_symmetry), held
// against exact answers: block-triangular matrices, and normal forms whose symmetric and
// symmetry-breaking multipliers are known in closed form.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/symmetry_reduction.hpp"
#include "sympathy/floquet/floquet.hpp"
#include "tests/support/cases.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::NormalForm;
using Kind = NormalForm::Kind;
using testing::kPi;

int count(const FloquetAnalysis& a, SymmetryKind kind) {
  int k = 0;
  for (const auto& m : a.multipliers) k += m.symmetry == kind;
  return k;
}

// The subspace z2 = z1 of R^3 and its complement: a matrix that maps the subspace into itself
// is block triangular there, whatever its other block. Built as Q diag-blocks Q^T with an
// across-to-inside coupling, its eigenvalues are exactly those of its blocks: 0.5 (inside,
// along (1,1,0)/sqrt 2), and 2 and -0.25 across. The labels must follow the blocks, not the
// sizes, in one segment and split over three segments alike.
TEST(SymmetryLabels, BlockTriangularMatricesAreLabelledByTheirBlocks) {
  const InvariantSubspace s(3, {{1, 0, 1.0}});
  const Eigen::MatrixXd in = s.basis(3), across = s.complement(3);
  ASSERT_EQ(in.cols(), 2);  // z1 = z2 (one direction) and z3 free
  ASSERT_EQ(across.cols(), 1);
  Eigen::MatrixXd q(3, 3);
  q << in, across;
  Eigen::MatrixXd blocks(3, 3);  // in the basis (in, across): inside block upper left
  blocks << 0.5, 0.3, 0.7, 0.0, -0.25, 0.4, 0.0, 0.0, 2.0;
  const Eigen::MatrixXd m = q * blocks * q.transpose();
  FloquetAnalysis a = analyze_floquet({m}, Eigen::VectorXd());
  label_symmetry(a, {m}, in, across);
  EXPECT_LT(a.symmetry_defect, 1e-15);
  for (const auto& mu : a.multipliers) {
    const bool breaking = std::abs(mu.value - 2.0) < 1e-12;
    EXPECT_EQ(mu.symmetry, breaking ? SymmetryKind::Breaking : SymmetryKind::Keeping) << mu.value;
  }
  // The same product in three factors: each factor block triangular in the same basis.
  Eigen::MatrixXd root(3, 3);  // any factor of that form: its cube is block triangular too
  root << 0.8, 0.1, 0.2, 0.0, -0.5, 0.1, 0.0, 0.0, 1.25;
  const Eigen::MatrixXd f = q * root * q.transpose();
  FloquetAnalysis b = analyze_floquet({f, f, f}, Eigen::VectorXd());
  label_symmetry(b, {f, f, f}, in, across);
  EXPECT_EQ(count(b, SymmetryKind::Breaking), 1);
  for (const auto& mu : b.multipliers) {
    const bool breaking = std::abs(mu.value - std::pow(1.25, 3)) < 1e-12;
    EXPECT_EQ(mu.symmetry, breaking ? SymmetryKind::Breaking : SymmetryKind::Keeping) << mu.value;
  }
}

// A matrix that does not keep the subspace (it leaks across by 0.3) gets no labels.
TEST(SymmetryLabels, ALeakingSubspaceLeavesTheMultipliersUnlabelled) {
  const InvariantSubspace s(2, {{1, -1, 1.0}});  // z2 = 0
  Eigen::MatrixXd m(2, 2);
  m << 0.5, 0.0, 0.3, 2.0;  // maps e1 to (0.5, 0.3): out of z2 = 0
  FloquetAnalysis a = analyze_floquet({m}, Eigen::VectorXd());
  label_symmetry(a, {m}, s.basis(2), s.complement(2));
  EXPECT_GT(a.symmetry_defect, 0.1);
  EXPECT_EQ(count(a, SymmetryKind::Unlabelled), 2);
}

// The transverse pitchfork normal form on its invariant plane w = 0 (tests/support): the
// multipliers are exactly 1 (trivial) and exp(-4 pi) (radial, r' = r (1 - r^2)), which keep
// w = 0, and exp(2 pi mu) (w' = mu w), which breaks it. Along the branch, its crossing of +1 at
// mu = 0 is the branch point, and it says it breaks w = 0.
TEST(SymmetryLabels, PitchforkBreaksItsPlaneExactly) {
  NormalForm system(Kind::Pitchfork, -0.4);
  const InvariantSubspace plane(3, {{2, -1, 1.0}}, "w1 = 0");
  Eigen::VectorXd z = Eigen::VectorXd::Zero(3);
  z[0] = 1.0;
  const PeriodicOrbit orbit =
      solve_periodic_orbit(system, system.default_parameters(), z, 2 * kPi, plane, OrbitOptions{});
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  for (const auto& m : orbit.floquet.multipliers) {
    if (std::abs(m.value - std::exp(2 * kPi * -0.4)) < 1e-7)
      EXPECT_EQ(m.symmetry, SymmetryKind::Breaking) << m.value;
    else
      EXPECT_EQ(m.symmetry, SymmetryKind::Keeping) << m.value;
  }
  EXPECT_EQ(count(orbit.floquet, SymmetryKind::Breaking), 1);

  ContinuationOptions o;
  o.lower = -0.5;
  o.upper = 0.5;
  Continuation c(system, 0, o);
  const Branch branch = c.run(orbit, +1);
  ASSERT_EQ(branch.events.size(), 1u) << branch.stop_reason;
  EXPECT_EQ(branch.events[0].type, BifurcationType::BranchPoint);
  EXPECT_NEAR(branch.events[0].parameter, 0.0, 1e-8);
  EXPECT_EQ(branch.events[0].symmetry, SymmetryKind::Breaking);
  for (const auto& p : branch.points) EXPECT_EQ(count(p.orbit.floquet, SymmetryKind::Breaking), 1);
}

// The transverse rotation normal form on (u, v) = 0: the Neimark-Sacker pair exp(2 pi (mu +-
// 0.3 i)) breaks the plane, the trivial and radial multipliers keep it.
TEST(SymmetryLabels, NeimarkSackerPairBreaksItsPlane) {
  NormalForm system(Kind::Rotation, -0.2);
  const InvariantSubspace plane(4, {{2, -1, 1.0}, {3, -1, 1.0}}, "u = v = 0");
  Eigen::VectorXd z = Eigen::VectorXd::Zero(4);
  z[0] = 1.0;
  const PeriodicOrbit orbit =
      solve_periodic_orbit(system, system.default_parameters(), z, 2 * kPi, plane, OrbitOptions{});
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  const std::complex<double> pair = std::exp(2 * kPi * std::complex<double>(-0.2, 0.3));
  for (const auto& m : orbit.floquet.multipliers) {
    const bool in_pair =
        std::abs(m.value - pair) < 1e-7 || std::abs(m.value - std::conj(pair)) < 1e-7;
    EXPECT_EQ(m.symmetry, in_pair ? SymmetryKind::Breaking : SymmetryKind::Keeping) << m.value;
  }
  EXPECT_EQ(count(orbit.floquet, SymmetryKind::Breaking), 2);
}

// The row setup at Table II: the anti-phase subspace x = 0, th2 = -th1 holds th1 and its
// velocity (2 of 6 directions: the trivial multiplier and one more keep it, 4 break it); the
// in-phase subspace th2 = th1 holds x, th1 and their velocities (4 keep it, 2 break it). Every
// multiplier keeps its value: the labels only sort them.
TEST(SymmetryLabels, RowSetupSubspacesSplitTheMultipliers) {
  const CaseFile file = CaseFile::load(testing::case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  for (const auto& [start, keeping] : {std::pair{"anti-phase", 2}, std::pair{"in-phase", 4}}) {
    const StartSpec& s = file.start(start);
    const PeriodicOrbit orbit =
        find_periodic_orbit(model, model.default_parameters(), file.initial_state(&s),
                            file.invariant_subspace(s, model), OrbitOptions{});
    ASSERT_TRUE(orbit.converged()) << start;
    EXPECT_EQ(count(orbit.floquet, SymmetryKind::Keeping), keeping) << start;
    EXPECT_EQ(count(orbit.floquet, SymmetryKind::Breaking), 6 - keeping) << start;
    EXPECT_EQ(orbit.floquet.multipliers[orbit.floquet.trivial].symmetry, SymmetryKind::Keeping);
    EXPECT_LT(orbit.floquet.symmetry_defect, 1e-8) << start;  // invariant to the integration
  }
}

// The cross setup's in-in orbit lies in th2 = th3 = th4 = th1, y = 0 (x, th1 and their
// velocities: 4 of 12 directions keep it), and carries a family (the free phase between the
// pairs) whose structural multiplier sits at 1 beside the trivial one: the trivial one must keep
// the symmetry (f lies in the subspace), the family's break it (the pairs drift apart).
TEST(SymmetryLabels, TrivialMultiplierKeepsTheSymmetryBesideAFamily) {
  const CaseFile file = CaseFile::load(testing::case_path("cross4"));
  const MetronomeModel model(file.spec("table4"));
  const StartSpec& s = file.start("in-in");
  const PeriodicOrbit orbit =
      find_periodic_orbit(model, model.default_parameters(), file.initial_state(&s),
                          file.invariant_subspace(s, model), OrbitOptions{});
  ASSERT_TRUE(orbit.converged());
  ASSERT_GE(orbit.floquet.trivial, 0);
  EXPECT_EQ(orbit.floquet.multipliers[orbit.floquet.trivial].symmetry, SymmetryKind::Keeping);
  for (const auto& m : orbit.floquet.multipliers) {
    if (m.structural) {
      EXPECT_EQ(m.symmetry, SymmetryKind::Breaking);
    }
  }
  EXPECT_EQ(count(orbit.floquet, SymmetryKind::Keeping), 4);
  EXPECT_EQ(count(orbit.floquet, SymmetryKind::Breaking), 8);
}

// N identical metronomes in a row (cases/row, Table II's platform times N/2): on the in-phase
// orbit every pendulum moves as in the row setup's in-phase orbit (the platform equation divided
// by N/2 is row2's), so the period and the multipliers that keep th_i = th1 are row2's, and the
// perturbations that break it (differences of pendula, which leave the platform alone) evolve as
// row2's antisymmetric one: its pair, N - 1 times (the permutations' standard representation).
// Tolerance 1e-8: the multipliers' own accuracy at rtol 1e-11.
TEST(SymmetryLabels, IdenticalMetronomesRepeatTheirBreakingPair) {
  auto in_phase = [](const std::string& name) {
    const CaseFile file = CaseFile::load(testing::case_path(name));
    const MetronomeModel model(file.spec());
    const StartSpec& s = file.start("in-phase");
    return find_periodic_orbit(model, model.default_parameters(), file.initial_state(&s),
                               file.invariant_subspace(s, model), OrbitOptions{});
  };
  const PeriodicOrbit two = in_phase("row2");
  ASSERT_TRUE(two.converged());
  std::vector<std::complex<double>> keeping, breaking;
  for (const auto& m : two.floquet.multipliers)
    (m.symmetry == SymmetryKind::Breaking ? breaking : keeping).push_back(m.value);
  ASSERT_EQ(breaking.size(), 2u);
  for (int n : {4, 8}) {
    const PeriodicOrbit orbit = in_phase("row/row" + std::to_string(n));
    ASSERT_TRUE(orbit.converged()) << n;
    EXPECT_NEAR(orbit.period, two.period, 1e-9) << n;
    int kept = 0, broken = 0;
    for (const auto& m : orbit.floquet.multipliers) {
      const auto& expected = m.symmetry == SymmetryKind::Breaking ? breaking : keeping;
      double nearest = 1.0;
      for (const auto& e : expected) nearest = std::min(nearest, std::abs(m.value - e));
      EXPECT_LT(nearest, 1e-8) << n << ": " << m.value;
      (m.symmetry == SymmetryKind::Breaking ? broken : kept) += 1;
    }
    EXPECT_EQ(kept, 4) << n;
    EXPECT_EQ(broken, 2 * (n - 1)) << n;
  }
}

// repeat_breaking: each breaking run (a pair, or a real one) repeated in place, the order by
// modulus kept, the summary recounted.
TEST(SymmetryLabels, RepeatBreakingKeepsPairsTogether) {
  FloquetAnalysis a;
  auto mu = [](std::complex<double> v, SymmetryKind kind, bool trivial = false) {
    Multiplier m;
    m.value = v;
    m.log_modulus = std::log(std::abs(v));
    m.symmetry = kind;
    m.trivial = trivial;
    return m;
  };
  const std::complex<double> pair = std::polar(1.2, 0.3);
  a.multipliers = {mu(pair, SymmetryKind::Breaking), mu(std::conj(pair), SymmetryKind::Breaking),
                   mu(1.0, SymmetryKind::Keeping, true), mu(-0.5, SymmetryKind::Breaking),
                   mu(0.1, SymmetryKind::Keeping)};
  const FloquetAnalysis r = repeat_breaking(a, 3, FloquetOptions{});
  ASSERT_EQ(r.multipliers.size(), 11u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(r.multipliers[2 * c].value, pair);
    EXPECT_EQ(r.multipliers[2 * c + 1].value, std::conj(pair));
    EXPECT_EQ(r.multipliers[7 + c].value, -0.5);
  }
  EXPECT_EQ(r.trivial, 6);
  EXPECT_EQ(r.unstable_count, 6);
  EXPECT_EQ(r.stability, Stability::Unstable);
  EXPECT_EQ(count(r, SymmetryKind::Breaking), 9);
}

// The in-phase orbit of N identical metronomes computed in the smallest block (the platform and
// two metronomes, the second standing for N - 1) against the same computation on the whole
// state: period, state and every multiplier to 1e-8 (the multipliers' own accuracy at rtol
// 1e-11) at N = 4 and 8. Detuning one metronome leaves no permutation symmetry: the whole state
// is computed, and says so.
TEST(SymmetryLabels, ReducedOrbitOfIdenticalMetronomesIsTheWholeOne) {
  for (int n : {4, 8}) {
    const CaseFile file = CaseFile::load(testing::case_path("row/row" + std::to_string(n)));
    const MetronomeModel model(file.spec());
    const StartSpec& s = file.start("in-phase");
    const InvariantSubspace subspace = file.invariant_subspace(s, model);
    ASSERT_TRUE(subspace.symmetry().has_value());
    OrbitOptions whole;
    whole.use_symmetry = false;
    const PeriodicOrbit reduced = find_periodic_orbit(
        model, model.default_parameters(), file.initial_state(&s), subspace, OrbitOptions{});
    const PeriodicOrbit full = solve_periodic_orbit(
        model, model.default_parameters(), reduced.state0, reduced.period, subspace, whole);
    ASSERT_TRUE(reduced.converged() && full.converged()) << n;
    EXPECT_FALSE(reduced.reduction.empty());
    EXPECT_TRUE(full.reduction.empty());
    EXPECT_NEAR(reduced.period, full.period, 1e-9) << n;
    EXPECT_LT((reduced.state0 - full.state0).cwiseAbs().maxCoeff(), 1e-8) << n;
    ASSERT_EQ(reduced.floquet.multipliers.size(), full.floquet.multipliers.size());
    // Paired one to one (repeated ones in any order): each whole one has a reduced one of its
    // kind within 1e-8, used once.
    std::vector<bool> used(full.floquet.multipliers.size(), false);
    for (const auto& b : full.floquet.multipliers) {
      int best = -1;
      for (std::size_t i = 0; i < used.size(); ++i) {
        const auto& a = reduced.floquet.multipliers[i];
        if (used[i] || a.symmetry != b.symmetry || a.trivial != b.trivial) continue;
        if (best < 0 || std::abs(a.value - b.value) <
                            std::abs(reduced.floquet.multipliers[best].value - b.value))
          best = static_cast<int>(i);
      }
      ASSERT_GE(best, 0) << n << ": " << b.value;
      used[best] = true;
      EXPECT_LT(std::abs(reduced.floquet.multipliers[best].value - b.value), 1e-8)
          << n << ": " << b.value;
    }
    EXPECT_EQ(reduced.floquet.unstable_count, full.floquet.unstable_count);
    EXPECT_NEAR(reduced.floquet.trivial_error, full.floquet.trivial_error, 1e-8);
  }
  const CaseFile file = CaseFile::load(testing::case_path("row/row4"));
  const MetronomeModel alike(file.spec());
  const InvariantSubspace subspace = file.invariant_subspace(file.start("in-phase"), alike);
  EXPECT_TRUE(symmetry_reduction(alike, alike.default_parameters(), subspace).has_value());
  ModelSpec spec = file.spec();
  spec.set("d3", spec.get("d3") * (1.0 + 1e-3));
  const MetronomeModel detuned(spec);
  EXPECT_FALSE(symmetry_reduction(detuned, detuned.default_parameters(), subspace).has_value());
}

}  // namespace
}  // namespace sympathy
