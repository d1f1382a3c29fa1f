#include "sympathy/core/invariant_subspace.hpp"

#include <gtest/gtest.h>

#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

// The projection is orthogonal onto {z0 = z1 = -z2, z3 = 0}; conflicting signs force zero.
TEST(InvariantSubspace, OrthogonalProjection) {
  const InvariantSubspace s(5, {{1, 0, 1.0}, {2, 0, -1.0}, {3, -1, 1.0}});
  Eigen::VectorXd z(5);
  z << 1.0, 2.0, 0.0, 7.0, 4.0;
  const Eigen::VectorXd p = s.project(z);
  const double mean = (1.0 + 2.0 - 0.0) / 3.0;
  EXPECT_DOUBLE_EQ(p[0], mean);
  EXPECT_DOUBLE_EQ(p[1], mean);
  EXPECT_DOUBLE_EQ(p[2], -mean);
  EXPECT_EQ(p[3], 0.0);
  EXPECT_EQ(p[4], 4.0);
  EXPECT_LT((s.project(p) - p).norm(), 1e-15);  // idempotent
  EXPECT_NEAR((z - p).dot(p), 0.0, 1e-14);      // orthogonal
  const InvariantSubspace conflict(2, {{1, 0, 1.0}, {1, 0, -1.0}});
  EXPECT_EQ(conflict.project(Eigen::Vector2d(3.0, 5.0)).norm(), 0.0);
  EXPECT_THROW(InvariantSubspace(2, {{0, 2, 1.0}}), std::invalid_argument);
}

// Two identical oscillators keep {z2 = z0, z3 = z1} and {z2 = -z0, z3 = -z1}, not {z2 = z1}.
TEST(InvariantSubspace, InvarianceDefect) {
  testing::TwoHopf system;
  const Eigen::VectorXd scale = Eigen::VectorXd::Ones(4);
  const ParameterValues p = system.default_parameters();
  EXPECT_LT(InvariantSubspace(4, {{2, 0, 1.0}, {3, 1, 1.0}}).invariance_defect(system, p, scale),
            1e-15);
  EXPECT_LT(InvariantSubspace(4, {{2, 0, -1.0}, {3, 1, -1.0}}).invariance_defect(system, p, scale),
            1e-15);
  EXPECT_GT(InvariantSubspace(4, {{2, 1, 1.0}}).invariance_defect(system, p, scale), 1e-3);
}

// Coordinates: one per free component and per tied group that is not zero, its smallest
// component; embedding and restricting invert each other on the subspace.
TEST(InvariantSubspace, RepresentativeCoordinates) {
  const InvariantSubspace s(6, {{3, 1, -1.0}, {5, 1, 1.0}, {2, -1, 1.0}});
  const auto c = s.coordinates(6);
  EXPECT_EQ(c.representative, (std::vector<int>{0, 1, 4}));
  EXPECT_EQ(c.coordinate, (std::vector<int>{0, 1, -1, 1, 2, 1}));
  EXPECT_EQ(c.sign[3], -1.0);
  EXPECT_EQ(c.sign[5], 1.0);
  const Eigen::Vector3d y(0.5, -2.0, 3.0);
  Eigen::VectorXd z(6);
  z << 0.5, -2.0, 0.0, 2.0, 3.0, -2.0;
  EXPECT_EQ(c.embed(y), z);
  EXPECT_EQ(c.restrict(z), Eigen::VectorXd(y));
  EXPECT_EQ(s.project(z), z);
}

// Four units of two components: the fixed space of S_4 ties every unit to the first; inside the
// space where units 2-4 are alike (coordinates: unit 1, unit 2) it ties unit 2's coordinates to
// unit 1's.
TEST(InvariantSubspace, FixedSpaceOfPermutationsInsideALargerOne) {
  PermutationSymmetry symmetry;
  for (int u = 0; u < 4; ++u) symmetry.units.push_back({1 + u, 5 + u});
  const int n = 9;  // a platform component 0, then positions 1-4, velocities 5-8
  const InvariantSubspace fixed = InvariantSubspace::fixed_by(symmetry, n, "all alike");
  ASSERT_TRUE(fixed.symmetry().has_value());
  EXPECT_EQ(fixed.coordinates(n).size(), 3);
  const InvariantSubspace larger(n, {{3, 2, 1.0}, {4, 2, 1.0}, {7, 6, 1.0}, {8, 6, 1.0}});
  EXPECT_EQ(larger.coordinates(n).representative, (std::vector<int>{0, 1, 2, 5, 6}));
  const InvariantSubspace inside = fixed.within(larger, n);
  // In larger's coordinates (0, th1, th2, v1, v2): th2 = th1, v2 = v1.
  EXPECT_EQ(inside.coordinates(5).representative, (std::vector<int>{0, 1, 3}));
  EXPECT_THROW(larger.within(fixed, n), std::invalid_argument);  // not contained
  // The same relations declared by hand are recognized; others are not.
  const InvariantSubspace by_hand(
      n, {{2, 1, 1.0}, {3, 2, 1.0}, {4, 1, 1.0}, {6, 5, 1.0}, {7, 5, 1.0}, {8, 7, 1.0}});
  EXPECT_TRUE(by_hand.with_symmetry(symmetry, n).symmetry().has_value());
  EXPECT_THROW(larger.with_symmetry(symmetry, n), std::invalid_argument);
}

// Swapping two of three identical Hopf-like units is a symmetry of their sum-coupled system;
// detuning one unit's frequency shows in the defect.
TEST(InvariantSubspace, PermutationDefect) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 6);
  for (int u = 0; u < 3; ++u) {
    A(2 * u, 2 * u + 1) = 1.0;
    A(2 * u + 1, 2 * u) = -1.0;
    for (int v = 0; v < 3; ++v) A(2 * u + 1, 2 * v) += 0.1;  // coupled through the sum
  }
  PermutationSymmetry symmetry{{{0, 1}, {2, 3}, {4, 5}}, "units"};
  const Eigen::VectorXd scale = Eigen::VectorXd::Ones(6);
  const testing::LinearSystem alike(A);
  EXPECT_LT(symmetry.defect(alike, alike.default_parameters(), scale), 1e-15);
  A(5, 4) -= 1e-6;
  const testing::LinearSystem detuned(A);
  EXPECT_GT(symmetry.defect(detuned, detuned.default_parameters(), scale), 1e-8);
}

}  // namespace
}  // namespace sympathy
