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

}  // namespace
}  // namespace sympathy
