#include "sympathy/core/reduced_system.hpp"

#include <gtest/gtest.h>
#include <unsupported/Eigen/MatrixFunctions>

#include "sympathy/core/flow.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

// z' = s A z with A = [B C; C B] (2 x 2 blocks) keeps {z3 = z1, z4 = z2} and on it y' = s (B + C) y
// exactly, and {z3 = -z1, z4 = -z2} with y' = s (B - C) y: the restriction's rhs, Jacobian,
// variational right-hand side and parameter derivative are those matrices, to rounding.
TEST(ReducedSystem, LinearSystemRestrictsToItsBlocks) {
  Eigen::Matrix2d B, C;
  B << -0.3, 1.0, -2.0, -0.1;
  C << 0.2, -0.5, 0.7, 0.4;
  Eigen::MatrixXd A(4, 4);
  A << B, C, C, B;
  const testing::LinearSystem system(A);
  ParameterValues p = system.default_parameters();
  p[0] = 1.5;
  for (double sign : {1.0, -1.0}) {
    const InvariantSubspace subspace(4, {{2, 0, sign}, {3, 1, sign}});
    const ReducedSystem reduced(system, subspace);
    ASSERT_EQ(reduced.dimension(), 2);
    EXPECT_EQ(reduced.state_names(), (std::vector<std::string>{"z1", "z2"}));
    const Eigen::Matrix2d expected = 1.5 * (B + sign * C);
    const Eigen::Vector2d y(0.3, -0.8);
    EXPECT_LT((reduced.rhs(0.0, y, p) - expected * y).norm(), 1e-15);
    EXPECT_LT((reduced.jacobian(0.0, y, p) - expected).norm(), 1e-15);
    // Two state columns and one parameter column (df/ds = (B + sign C) y).
    Eigen::MatrixXd S(2, 3), out(2, 3);
    S << 1.0, 0.5, 0.2, -1.0, 2.0, 0.1;
    const double* in[] = {S.col(0).data(), S.col(1).data(), S.col(2).data()};
    double* res[] = {out.col(0).data(), out.col(1).data(), out.col(2).data()};
    const int parameter[] = {0};
    reduced.variational_rhs(0.0, y.data(), p.data(), 3, in, res, parameter);
    EXPECT_LT((out.leftCols(2) - expected * S.leftCols(2)).norm(), 1e-14);
    EXPECT_LT((out.col(2) - expected * S.col(2) - expected / 1.5 * y).norm(), 1e-14);
    // f and the columns in one call: the same, f within rounding of rhs's.
    Eigen::MatrixXd both(2, 3);
    double* res_both[] = {both.col(0).data(), both.col(1).data(), both.col(2).data()};
    Eigen::Vector2d f;
    reduced.rhs_and_variational(0.0, y.data(), p.data(), f.data(), 3, in, res_both, parameter);
    EXPECT_LT((f - expected * y).norm(), 1e-15);
    EXPECT_LT((both - out).norm(), 1e-15);
    Eigen::Vector2d dfdp;
    reduced.parameter_derivative(0.0, y.data(), p.data(), 0, dfdp.data());
    EXPECT_LT((dfdp - expected / 1.5 * y).norm(), 1e-15);
    // Its flow is the whole flow inside the subspace: exp(t s (B + sign C)).
    Flow flow(reduced);
    const auto d = flow.advance_with_sensitivities(y, p, 0.0, 1.0);
    const Eigen::MatrixXd phi = Eigen::MatrixXd(expected).exp();
    EXPECT_LT((d.transition - phi).norm(), 1e-8);
    EXPECT_LT((d.state - phi * y).norm(), 1e-8);
  }
}

// A restriction of a restriction (the per-thread scratch of the inner call is not the outer
// call's): z' = A z with A = diag(B, B, B) (2 x 2 blocks) keeps {z3 = z1, z4 = z2}, and within it
// {z5 = z1, z6 = z2}; the restriction twice over is y' = B y, its flow exp(t B).
TEST(ReducedSystem, RestrictionOfARestriction) {
  Eigen::Matrix2d B;
  B << -0.3, 1.0, -2.0, -0.1;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 6);
  for (int k = 0; k < 3; ++k) A.block(2 * k, 2 * k, 2, 2) = B;
  const testing::LinearSystem system(A);
  const ParameterValues p = system.default_parameters();
  const ReducedSystem once(system, InvariantSubspace(6, {{2, 0, 1.0}, {3, 1, 1.0}}));
  ASSERT_EQ(once.dimension(), 4);  // (z1, z2, z5, z6)
  const ReducedSystem twice(once, InvariantSubspace(4, {{2, 0, 1.0}, {3, 1, 1.0}}));
  ASSERT_EQ(twice.dimension(), 2);
  const Eigen::Vector2d y(0.3, -0.8);
  EXPECT_LT((twice.rhs(0.0, y, p) - p[0] * B * y).norm(), 1e-15);
  Eigen::Matrix2d S, out;
  S << 1.0, 0.5, -1.0, 2.0;
  const double* in[] = {S.col(0).data(), S.col(1).data()};
  double* res[] = {out.col(0).data(), out.col(1).data()};
  Eigen::Vector2d f;
  twice.rhs_and_variational(0.0, y.data(), p.data(), f.data(), 2, in, res, {});
  EXPECT_LT((f - p[0] * B * y).norm(), 1e-15);
  EXPECT_LT((out - p[0] * B * S).norm(), 1e-15);
  Flow flow(twice);
  const auto d = flow.advance_with_sensitivities(y, p, 0.0, 1.0);
  const Eigen::MatrixXd phi = Eigen::MatrixXd(p[0] * B).exp();
  EXPECT_LT((d.transition - phi).norm(), 1e-8);
  EXPECT_LT((d.state - phi * y).norm(), 1e-8);
}

// Zero components drop out; tied ones share one coordinate and its steep zone.
TEST(ReducedSystem, SteepZonesFollowTheirCoordinates) {
  const testing::Pulse system(0.01, 3);  // (u1, q1, u2, q2, u3, q3), zones on u1, u2, u3
  const InvariantSubspace subspace(6, {{2, 0, 1.0}, {4, 0, 1.0}, {5, -1, 1.0}});
  const ReducedSystem reduced(system, subspace);
  EXPECT_EQ(reduced.state_names(), (std::vector<std::string>{"u1", "q1", "q2"}));
  const auto zones = reduced.steep_zones(nullptr);
  ASSERT_EQ(zones.size(), 1u);
  EXPECT_EQ(zones[0].component, 0);
  EXPECT_EQ(zones[0].width, 0.01);
}

}  // namespace
}  // namespace sympathy
