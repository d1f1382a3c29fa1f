// The monodromy split by a reflection's isotypic blocks (core/across_variations.hpp) and the
// shooting problem that reuses a symmetric orbit the parameter does not move (shooting.hpp),
// against exact multipliers and against the whole computation.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/continuation/shooting.hpp"
#include "sympathy/core/across_variations.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/reduced_system.hpp"
#include "tests/support/cases.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::SymmetricPair;

using testing::kPi;

// SymmetricPair's anti-phase fixed space: x = 0, a2 = -a1, b2 = -b1.
InvariantSubspace pair_subspace() {
  return InvariantSubspace(5, {{4, -1, 1.0}, {2, 0, -1.0}, {3, 1, -1.0}}, "x = 0, z2 = -z1");
}

FlowOptions tight() {
  FlowOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  return o;
}

// Eigenvalue moduli, decreasing.
std::vector<double> moduli(const Eigen::MatrixXd& m) {
  const Eigen::VectorXcd ev = m.eigenvalues();
  std::vector<double> out;
  for (int i = 0; i < ev.size(); ++i) out.push_back(std::abs(ev[i]));
  std::sort(out.rbegin(), out.rend());
  return out;
}

// The monodromy of the whole system from z0 over T, and the blocks: V's (the restricted system's
// in V's coordinates, turned into the orthonormal basis) and W's (AcrossVariations).
struct Blocks {
  Eigen::MatrixXd whole, inside_of_whole, across_of_whole, coupling_of_whole;
  Eigen::MatrixXd inside, across;
};

Blocks blocks(const OdeSystem& system, const InvariantSubspace& subspace, const Eigen::VectorXd& z0,
              double T, const ParameterValues& p, const FlowOptions& options) {
  const int n = system.dimension();
  Blocks b;
  Flow whole(system, options);
  b.whole = whole.advance_with_sensitivities(z0, p, 0.0, T).transition;
  const Eigen::MatrixXd B = subspace.bases(n).inside;
  const Eigen::MatrixXd C = subspace.reflection(n)->breaking_basis();
  b.inside_of_whole = B.transpose() * b.whole * B;
  b.across_of_whole = C.transpose() * b.whole * C;
  b.coupling_of_whole = C.transpose() * b.whole * B;
  // V's block from the restricted system: y = R z, z = P y, so inside = B^T P M_y R B.
  const ReducedSystem reduced(system, subspace);
  Flow inner(reduced, options);
  const auto& k = reduced.coordinates();
  const Eigen::MatrixXd My = inner.advance_with_sensitivities(k.restrict(z0), p, 0.0, T).transition;
  b.inside = B.transpose() * k.embedding() * My * k.restriction() * B;
  const AcrossVariations across(system, subspace);
  Flow plain(across, options);
  b.across = across.block(plain.advance(across.start(z0), p, 0.0, T));
  return b;
}

// A shooting problem that samples its period (as a continuation's does), told `symmetry` where one
// is given.
std::unique_ptr<ShootingProblem> sampled_problem(const OdeSystem& system,
                                                 const ShootingOptions& options,
                                                 const InvariantSubspace* symmetry) {
  auto problem = std::make_unique<ShootingProblem>(system, options);
  problem->record_samples(true);
  if (symmetry) problem->use_symmetry(*symmetry);
  return problem;
}

// The branch's points first, first + size / 2, ...: each one's multipliers are those of Newton
// on the whole state (no symmetry) at its parameter values, from it, to `tolerance` (each to the
// nearest: a conjugate pair's order is arbitrary).
void expect_multipliers_of_the_whole(const OdeSystem& model, const Branch& branch,
                                     const InvariantSubspace& subspace, OrbitOptions whole,
                                     std::size_t first, double tolerance) {
  whole.use_symmetry = false;
  for (std::size_t i = first; i < branch.points.size(); i += branch.points.size() / 2) {
    const PeriodicOrbit& a = branch.points[i].orbit;
    const PeriodicOrbit b =
        solve_periodic_orbit(model, a.parameters, a.state0, a.period, subspace, whole);
    ASSERT_TRUE(b.converged()) << i;
    ASSERT_EQ(a.floquet.multipliers.size(), b.floquet.multipliers.size());
    for (const auto& m : a.floquet.multipliers) {
      double nearest = INFINITY;
      for (const auto& other : b.floquet.multipliers)
        nearest = std::min(nearest, std::abs(m.value - other.value));
      EXPECT_LT(nearest, tolerance) << i << " " << m.value;
    }
  }
}

// A subspace's coordinates as matrices: P y = embed(y) and R z = restrict(z) exactly, R P = I,
// and P R is the identity on the subspace (x = 0, a2 = -a1, b2 = -b1).
TEST(SymmetricBlocks, CoordinatesAsMatrices) {
  const auto k = pair_subspace().coordinates(5);
  const Eigen::MatrixXd P = k.embedding(), R = k.restriction();
  ASSERT_EQ(P.rows(), 5);
  ASSERT_EQ(P.cols(), 2);
  const Eigen::VectorXd y = (Eigen::VectorXd(2) << 0.3, -0.7).finished();
  const Eigen::VectorXd z = (Eigen::VectorXd(5) << 0.3, -0.7, 1.1, 0.2, -0.4).finished();
  EXPECT_EQ(P * y, k.embed(y));
  EXPECT_EQ(R * z, k.restrict(z));
  EXPECT_EQ(R * P, Eigen::MatrixXd::Identity(2, 2));
  const Eigen::VectorXd in_v = pair_subspace().project(z);
  EXPECT_LT((P * R * in_v - in_v).cwiseAbs().maxCoeff(), 1e-15);
}

// The reflection of a subspace of pairs and zeros: an involution that fixes the subspace and
// reverses the breaking basis, which is orthonormal and orthogonal to it; none for a group of
// three or for the whole space.
TEST(SymmetricBlocks, ReflectionOfPairsAndZeros) {
  const InvariantSubspace v = pair_subspace();
  const auto g = v.reflection(5);
  ASSERT_TRUE(g);
  const Eigen::MatrixXd C = g->breaking_basis();
  ASSERT_EQ(C.cols(), 3);
  EXPECT_LT((C.transpose() * C - Eigen::MatrixXd::Identity(3, 3)).norm(), 1e-15);
  const Eigen::VectorXd z = (Eigen::VectorXd(5) << 0.3, -0.7, 1.1, 0.2, -0.4).finished();
  EXPECT_EQ(g->apply(g->apply(z)), z);
  const Eigen::VectorXd inside = v.project(z);
  EXPECT_LT((g->apply(inside) - inside).norm(), 1e-15);
  for (int j = 0; j < 3; ++j) {
    EXPECT_LT((g->apply(C.col(j)) + C.col(j)).norm(), 1e-15) << j;
    EXPECT_LT(v.project(C.col(j)).norm(), 1e-15) << j;
  }
  EXPECT_FALSE(InvariantSubspace(3, {{1, 0, 1.0}, {2, 0, 1.0}}).reflection(3));
  EXPECT_FALSE(InvariantSubspace().reflection(3));
}

// SymmetricPair at eps = 0 (header): the blocks' multipliers are exactly known, inside {1,
// exp(-4 pi)}, across {exp(-4 pi kappa), exp(-4 pi (1 + kappa)), exp(-2 pi gamma)} (w = 1,
// kappa = 0.1, gamma = 0.5); each block to 1e-9 (rtol 1e-11: the multipliers' errors are about
// 100 rtol), and the split equals the whole monodromy's blocks to 1e-10.
TEST(SymmetricBlocks, KnownMultipliersOfTheBlocks) {
  const SymmetricPair system;
  const ParameterValues p = system.default_parameters();
  const Eigen::VectorXd z0 = (Eigen::VectorXd(5) << 1.0, 0.0, -1.0, 0.0, 0.0).finished();
  const Blocks b = blocks(system, pair_subspace(), z0, 2.0 * kPi, p, tight());
  const std::vector<double> inside = moduli(b.inside), across = moduli(b.across);
  EXPECT_NEAR(inside[0], 1.0, 1e-9);
  EXPECT_NEAR(inside[1], std::exp(-4.0 * kPi), 1e-9);
  EXPECT_NEAR(across[0], std::exp(-0.4 * kPi), 1e-9);
  EXPECT_NEAR(across[1], std::exp(-kPi), 1e-9);
  EXPECT_NEAR(across[2], std::exp(-4.4 * kPi), 1e-9);
  EXPECT_LT((b.inside - b.inside_of_whole).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT((b.across - b.across_of_whole).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT(b.coupling_of_whole.cwiseAbs().maxCoeff(), 1e-12);
}

// With the platform feeding back (eps = 0.2) the across block has no closed form: the split
// equals the whole monodromy's blocks to 1e-10.
TEST(SymmetricBlocks, SplitEqualsWholeMonodromyWithFeedback) {
  const SymmetricPair system(0.2);
  const Eigen::VectorXd z0 = (Eigen::VectorXd(5) << 1.0, 0.0, -1.0, 0.0, 0.0).finished();
  const Blocks b =
      blocks(system, pair_subspace(), z0, 2.0 * kPi, system.default_parameters(), tight());
  EXPECT_LT((b.inside - b.inside_of_whole).cwiseAbs().maxCoeff(), 1e-10);
  EXPECT_LT((b.across - b.across_of_whole).cwiseAbs().maxCoeff(), 1e-10);
}

// The row setup's anti-phase orbit at Table II: the 2 x 2 and 4 x 4 blocks equal the whole 6 x 6
// monodromy's to 1e-10 relative to its largest entry (about 11; rtol 1e-13, the turning points
// resolved in each run; at rtol 1e-11 the runs differ by 8e-9, their own integration error), and
// the whole one has no coupling between them.
TEST(SymmetricBlocks, AntiPhaseOrbitOfTheRowSetup) {
  const CaseFile file = CaseFile::load(testing::case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  const StartSpec& start = file.start("anti-phase");
  const InvariantSubspace subspace = file.invariant_subspace(start, model);
  ASSERT_TRUE(subspace.reflection(6));
  OrbitOptions options;
  options.shooting.flow = tight();
  // From where the whole 60 s transient ends, as when the tolerance below was set: the runs'
  // difference depends on where on the orbit they start (from the point Newton tried at 12 s
  // lands on, OrbitOptions::early_newton_below, 1.6e-9: 1.5e-10 of the largest entry).
  options.early_newton_below = 0.0;
  const PeriodicOrbit orbit = find_periodic_orbit(model, model.default_parameters(),
                                                  file.initial_state(&start), subspace, options);
  ASSERT_TRUE(orbit.converged());
  FlowOptions tightest = tight();
  tightest.rtol = 1e-13;
  tightest.atol = 1e-15;
  const Blocks b = blocks(model, subspace, orbit.state0, orbit.period, orbit.parameters, tightest);
  EXPECT_EQ(b.inside.rows(), 2);
  EXPECT_EQ(b.across.rows(), 4);
  const double size = b.whole.cwiseAbs().maxCoeff();  // about 11
  EXPECT_LT((b.inside - b.inside_of_whole).cwiseAbs().maxCoeff(), 1e-10 * size);
  EXPECT_LT((b.across - b.across_of_whole).cwiseAbs().maxCoeff(), 1e-10 * size);
  EXPECT_LT(b.coupling_of_whole.cwiseAbs().maxCoeff(), 1e-10 * size);
}

// A shooting problem told the symmetry: at a new gamma (which acts only across V) it serves the
// evaluation from the across block, equal to the whole evaluation there to 1e-9 (residual,
// monodromy) with a zero parameter column; at a new w (which moves the orbit) it refuses and
// computes the whole, as a problem without symmetry does.
TEST(SymmetricBlocks, ShootingReusesTheOrbitOnlyWhereTheParameterLeavesIt) {
  const SymmetricPair system(0.2);
  const ParameterValues p0 = system.default_parameters();
  ShootingOptions options;
  options.flow = tight();
  const Eigen::VectorXd z0 = (Eigen::VectorXd(5) << 1.0, 0.0, -1.0, 0.0, 0.0).finished();
  const InvariantSubspace subspace = pair_subspace();
  auto symmetric = sampled_problem(system, options, &subspace);
  auto whole = sampled_problem(system, options, nullptr);
  const PhaseSection section = whole->section_through(z0, p0);
  const Eigen::VectorXd x = symmetric->unknowns_from(z0, p0, 2.0 * kPi);
  whole->unknowns_from(z0, p0, 2.0 * kPi);
  const int gamma = system.parameter_index("gamma"), w = system.parameter_index("w");
  symmetric->evaluate(x, p0, section, true, gamma);  // remembered
  EXPECT_EQ(symmetric->across_evaluations(), 0);
  const ParameterValues p1 = system.with_parameter(p0, gamma, 1.3);
  const auto a = symmetric->evaluate(x, p1, section, true, gamma);
  EXPECT_EQ(symmetric->across_evaluations(), 1);
  const auto b = whole->evaluate(x, p1, section, true, gamma);
  EXPECT_LT((a.residual - b.residual).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((a.transitions[0] - b.transitions[0]).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_EQ(a.parameter_sensitivities.cwiseAbs().maxCoeff(), 0.0);
  EXPECT_LT(b.parameter_sensitivities.cwiseAbs().maxCoeff(), 1e-12);
  const ParameterValues p2 = system.with_parameter(p0, w, 1.1);
  const auto c = symmetric->evaluate(x, p2, section, true, w);
  const auto d = whole->evaluate(x, p2, section, true, w);
  EXPECT_EQ(symmetric->across_evaluations(), 1);  // not served: w moves the orbit
  EXPECT_LT((c.residual - d.residual).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((c.transitions[0] - d.transitions[0]).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(c.parameter_sensitivities.cwiseAbs().maxCoeff(), 0.1);
}

// A branch in V is kept there exactly (ShootingProblem::keep_in_subspace): the anti-phase orbit's
// start (1, 0, -1, 0, 0) moved off V by rounding (1e-15) comes back into V exactly (its nearest
// point there, within 2e-16 of the start), the period untouched; moved by 1e-9 (past the 1e-13 of
// the state's size that counts as rounding) it is left as it is. A direction's part in V
// (project_on_subspace) is the orthogonal projection onto x = 0, a2 = -a1, b2 = -b1, exactly: (a1 -
// a2)/2, (b1 - b2)/2, their negatives, 0. Without a symmetry declared, both leave their vector
// alone.
TEST(SymmetricBlocks, BranchKeptInItsSubspaceExactly) {
  const SymmetricPair system(0.2);
  const ParameterValues p = system.default_parameters();
  ShootingOptions options;
  options.flow = tight();
  const Eigen::VectorXd z0 = (Eigen::VectorXd(5) << 1.0, 0.0, -1.0, 0.0, 0.0).finished();
  const InvariantSubspace subspace = pair_subspace();
  auto symmetric = sampled_problem(system, options, &subspace);
  auto whole = sampled_problem(system, options, nullptr);
  const Eigen::VectorXd x = symmetric->unknowns_from(z0, p, 2.0 * kPi);
  Eigen::VectorXd off = x;
  off[2] += 2e-16;
  off[4] = 1e-15;
  ASSERT_TRUE(symmetric->keep_in_subspace(off, p));
  EXPECT_LT((off.head(5) - z0).cwiseAbs().maxCoeff(), 2e-16);
  EXPECT_EQ(off[2], -off[0]);  // exactly in V
  EXPECT_EQ(off[3], -off[1]);
  EXPECT_EQ(off[4], 0.0);
  EXPECT_EQ(off.tail(off.size() - 5), x.tail(x.size() - 5));
  Eigen::VectorXd far = x;
  far[4] = 1e-9;
  const Eigen::VectorXd far_before = far;
  EXPECT_FALSE(symmetric->keep_in_subspace(far, p));
  EXPECT_EQ(far, far_before);
  Eigen::VectorXd unchanged = off;
  unchanged[4] = 1e-15;
  EXPECT_FALSE(whole->keep_in_subspace(unchanged, p));
  EXPECT_EQ(unchanged[4], 1e-15);

  Eigen::VectorXd direction(7);
  direction << 0.3, 0.1, 0.5, -0.2, 0.7, 0.25, -0.5;  // the state's 5, then two more entries
  Eigen::VectorXd projected = direction;
  symmetric->project_on_subspace(projected);
  const Eigen::VectorXd expected =
      (Eigen::VectorXd(7) << -0.1, 0.15, 0.1, -0.15, 0.0, 0.25, -0.5).finished();
  EXPECT_LT((projected - expected).cwiseAbs().maxCoeff(), 1e-16);
  EXPECT_EQ(projected[2], -projected[0]);  // exactly in V
  EXPECT_EQ(projected[3], -projected[1]);
  EXPECT_EQ(projected[4], 0.0);
  Eigen::VectorXd left = direction;
  whole->project_on_subspace(left);
  EXPECT_EQ(left, direction);
}

// Augmented Adams at rtol 1e-11, as the default preset integrates.
FlowOptions augmented() {
  FlowOptions o = tight();
  o.method = Method::Adams;
  o.nonlinear_solver = NonlinearSolver::FixedPoint;
  o.sensitivities = Sensitivities::Augmented;
  return o;
}

// An orbit in V that the parameter moves (w, SymmetricPair at eps = 0): with augmented
// sensitivities the evaluation integrates V's block with its parameter column and W's block in
// one run. Exact answers: over T = 2 pi from z0 = (1, 0, -1, 0, 0), z(T) = (cos wT, sin wT, ...),
// so dz(T)/dw = T (-sin wT, cos wT, sin wT, -cos wT, 0) = (0, 2 pi, 0, -2 pi, 0) at w = 1, and
// the monodromy's moduli are {1, exp(-4 pi)} inside and {exp(-0.4 pi), exp(-pi), exp(-4.4 pi)}
// across (SymmetricPair); each to 1e-8 (rtol 1e-11). Against the whole evaluation (no symmetry)
// residual, monodromy and column to 1e-9; the samples are the orbit's (the whole run's to 1e-9).
TEST(SymmetricBlocks, SplitEvaluationOfAnOrbitThatMovesEqualsTheWhole) {
  const SymmetricPair system;
  const ParameterValues p = system.default_parameters();
  ShootingOptions options;
  options.flow = augmented();
  const Eigen::VectorXd z0 = (Eigen::VectorXd(5) << 1.0, 0.0, -1.0, 0.0, 0.0).finished();
  const InvariantSubspace subspace = pair_subspace();
  auto split = sampled_problem(system, options, &subspace);
  auto whole = sampled_problem(system, options, nullptr);
  const PhaseSection section = whole->section_through(z0, p);
  Eigen::VectorXd x(6);
  x << z0, 2.0 * kPi;
  const int w = system.parameter_index("w");
  const auto a = split->evaluate(x, p, section, true, w);
  EXPECT_EQ(split->split_evaluations(), 1);
  EXPECT_EQ(split->across_evaluations(), 0);
  const auto b = whole->evaluate(x, p, section, true, w);
  EXPECT_EQ(whole->split_evaluations(), 0);
  const Eigen::VectorXd exact_column =
      (Eigen::VectorXd(5) << 0.0, 2.0 * kPi, 0.0, -2.0 * kPi, 0.0).finished();
  EXPECT_LT((a.parameter_sensitivities.col(0) - exact_column).cwiseAbs().maxCoeff(), 1e-8);
  std::vector<double> expected{1.0, std::exp(-4.0 * kPi), std::exp(-0.4 * kPi), std::exp(-kPi),
                               std::exp(-4.4 * kPi)};
  std::sort(expected.rbegin(), expected.rend());
  const std::vector<double> found = moduli(a.transitions[0]);
  for (int i = 0; i < 5; ++i) EXPECT_NEAR(found[i], expected[i], 1e-8) << i;
  EXPECT_LT(a.residual.cwiseAbs().maxCoeff(), 1e-9);  // the orbit closes
  EXPECT_LT((a.residual - b.residual).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((a.transitions[0] - b.transitions[0]).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((a.parameter_sensitivities - b.parameter_sensitivities).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_LT((a.end_rates[0] - b.end_rates[0]).cwiseAbs().maxCoeff(), 1e-9);
  ASSERT_TRUE(a.samples.of(z0, 2.0 * kPi));
  EXPECT_LT((a.samples.states - b.samples.states).cwiseAbs().maxCoeff(), 1e-9);
  // The plain residual integrates the orbit in V alone: the whole problem's to 1e-9.
  EXPECT_LT((split->residual(x, p, section) - whole->residual(x, p, section)).cwiseAbs().maxCoeff(),
            1e-9);
}

// A parameter that detunes the reflection (the second metronome's pendulum length lp2, on the row
// setup's in-phase orbit) moves the orbit off V: its column has a part across V, which V's block
// cannot carry. The split refuses it and the whole evaluation runs: the column's th1 and th2
// entries differ by more than a tenth of their size, as without symmetry (to 1e-9); k keeps the
// reflection and is served split, equal to the whole to 1e-8 relative (the monodromy's largest
// entry is about 10; rtol 1e-11).
TEST(SymmetricBlocks, SplitRefusesAParameterThatDetunesTheReflection) {
  const CaseFile file = CaseFile::load(testing::case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  const StartSpec& start = file.start("in-phase");
  const InvariantSubspace subspace = file.invariant_subspace(start, model);
  OrbitOptions orbit_options;
  orbit_options.shooting.flow = augmented();
  const PeriodicOrbit orbit = find_periodic_orbit(
      model, model.default_parameters(), file.initial_state(&start), subspace, orbit_options);
  ASSERT_TRUE(orbit.converged());
  ShootingOptions options;
  options.flow = augmented();
  auto split = sampled_problem(model, options, &subspace);
  auto whole = sampled_problem(model, options, nullptr);
  const PhaseSection section = whole->section_through(orbit.state0, orbit.parameters);
  const Eigen::VectorXd x = split->unknowns_from(orbit.state0, orbit.parameters, orbit.period);
  whole->unknowns_from(orbit.state0, orbit.parameters, orbit.period);
  const auto names = model.state_names();
  const auto at = [&](const std::string& name) {
    return static_cast<int>(std::find(names.begin(), names.end(), name) - names.begin());
  };
  const int th1 = at("th1"), th2 = at("th2");
  ASSERT_LT(th2, 6);
  const int lp2 = model.parameter_index("lp2");
  const auto a = split->evaluate(x, orbit.parameters, section, true, lp2);
  EXPECT_EQ(split->split_evaluations(), 0);
  const auto b = whole->evaluate(x, orbit.parameters, section, true, lp2);
  const Eigen::VectorXd column = a.parameter_sensitivities.col(0);
  EXPECT_GT(std::abs(column[th1] - column[th2]),
            0.1 * std::max(std::abs(column[th1]), std::abs(column[th2])));
  EXPECT_LT((column - b.parameter_sensitivities.col(0)).cwiseAbs().maxCoeff(), 1e-9);
  const int k = model.parameter_index("k");
  const auto c = split->evaluate(x, orbit.parameters, section, true, k);
  EXPECT_EQ(split->split_evaluations(), 1);
  const auto d = whole->evaluate(x, orbit.parameters, section, true, k);
  const double size = d.transitions[0].cwiseAbs().maxCoeff();
  EXPECT_LT((c.transitions[0] - d.transitions[0]).cwiseAbs().maxCoeff(), 1e-8 * size);
  EXPECT_LT((c.parameter_sensitivities - d.parameter_sensitivities).cwiseAbs().maxCoeff(),
            1e-8 * d.parameter_sensitivities.cwiseAbs().maxCoeff());
  EXPECT_LT((c.residual - d.residual).cwiseAbs().maxCoeff(), 1e-9);
}

// A gamma-branch of SymmetricPair (eps = 0) from 0.5 to 2: every point's across multiplier
// exp(-2 pi gamma) and the others exactly known, to 1e-8, the breaking ones labelled so, and all
// points after the first served by the across block. The same branch in w (which moves the
// orbit): every point computed whole, its period 2 pi / w to 1e-9.
TEST(SymmetricBlocks, BranchInAParameterThatActsAcross) {
  const SymmetricPair system;
  BranchProblem problem;
  problem.parameter = system.parameter_index("gamma");
  problem.values = system.default_parameters();
  problem.from = 0.5;
  problem.to = 2.0;
  problem.start_state = (Eigen::VectorXd(5) << 1.0, 0.0, -1.0, 0.0, 0.0).finished();
  problem.subspace = pair_subspace();
  ContinuationOptions options;
  options.orbit.shooting.flow = tight();
  const Branch branch = continue_branch(system, problem, options);
  ASSERT_TRUE(branch.started());
  ASSERT_GE(branch.points.size(), 5u);
  EXPECT_GT(branch.across_evaluations, 0);
  for (const auto& point : branch.points) {
    const double gamma = system.parameter(point.orbit.parameters, problem.parameter);
    std::vector<double> keeping, breaking;
    for (const auto& m : point.orbit.floquet.multipliers)
      (m.symmetry == SymmetryKind::Breaking ? breaking : keeping).push_back(m.modulus());
    ASSERT_EQ(keeping.size(), 2u);
    ASSERT_EQ(breaking.size(), 3u);
    std::sort(breaking.rbegin(), breaking.rend());
    std::vector<double> expected{std::exp(-0.4 * kPi), std::exp(-2.0 * kPi * gamma),
                                 std::exp(-4.4 * kPi)};
    std::sort(expected.rbegin(), expected.rend());
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(breaking[i], expected[i], 1e-8) << gamma;
    EXPECT_NEAR(point.orbit.period, 2.0 * kPi, 1e-9);
  }
  problem.parameter = system.parameter_index("w");
  problem.from = 1.0;
  problem.to = 1.3;
  const Branch moving = continue_branch(system, problem, options);
  ASSERT_TRUE(moving.started());
  ASSERT_GE(moving.points.size(), 3u);
  EXPECT_EQ(moving.across_evaluations, 0);
  for (const auto& point : moving.points) {
    const double w = system.parameter(point.orbit.parameters, problem.parameter);
    EXPECT_NEAR(point.orbit.period, 2.0 * kPi / w, 1e-9) << w;
  }
}

// The row setup at Table II, k from 14.7 to 20 N/m at the library's defaults: on the anti-phase
// branch (the platform still: k acts only across the subspace) the points after the first are
// served by the across block, and their multipliers are those of Newton on the whole state at
// the same k to 1e-8 (both at rtol 1e-11: the multipliers' own accuracy is about 2e-9); on the
// in-phase branch (th2 = th1 is a reflection's fixed space too, but the platform moves and the
// orbit with k) none is.
TEST(SymmetricBlocks, RowSetupAntiPhaseServedInPhaseNot) {
  const CaseFile file = CaseFile::load(testing::case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  auto branch_from = [&](const std::string& name) {
    const BranchProblem problem = testing::branch_problem(file, model, name, "k", 20.0);
    return std::pair{continue_branch(model, problem, ContinuationOptions{}), problem.subspace};
  };
  const auto [anti, subspace] = branch_from("anti-phase");
  ASSERT_TRUE(anti.started());
  ASSERT_GE(anti.points.size(), 3u);
  EXPECT_GE(anti.across_evaluations, static_cast<int>(anti.points.size()) - 1);
  expect_multipliers_of_the_whole(model, anti, subspace, OrbitOptions{}, 1, 1e-8);
  const auto [in, in_subspace] = branch_from("in-phase");
  ASSERT_TRUE(in.started());
  ASSERT_TRUE(in_subspace.reflection(6));
  EXPECT_EQ(in.across_evaluations, 0);
}

// The in-phase branch of the same stretch with augmented sensitivities (the default preset's
// kind): its points are integrated block by block (the orbit with V's block and parameter column,
// and W's block, in one run; split_evaluation) and plain residuals in V alone. Each point's
// multipliers are those of Newton on the whole state at the same k to 1e-8 (rtol 1e-11: the
// multipliers' own accuracy is about 2e-9), and the trivial one is 1 to 1e-8.
TEST(SymmetricBlocks, RowSetupInPhaseBranchSplitAgreesWithTheWhole) {
  const CaseFile file = CaseFile::load(testing::case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  const BranchProblem problem = testing::branch_problem(file, model, "in-phase", "k", 20.0);
  ContinuationOptions options;
  options.orbit.shooting.flow = augmented();
  const Branch branch = continue_branch(model, problem, options);
  ASSERT_TRUE(branch.started());
  ASSERT_GE(branch.points.size(), 3u);
  EXPECT_GE(branch.split_evaluations, static_cast<int>(branch.points.size()));
  for (const auto& point : branch.points) EXPECT_LT(point.orbit.floquet.trivial_error, 1e-8);
  OrbitOptions whole;
  whole.shooting.flow = augmented();
  expect_multipliers_of_the_whole(model, branch, problem.subspace, whole, 0, 1e-8);
}

}  // namespace
}  // namespace sympathy
