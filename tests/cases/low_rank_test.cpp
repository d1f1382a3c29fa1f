// The metronome model's Jacobian in low-rank form, df/dz = S + U W^T (S sparse, rank = platform
// directions), and the low-rank solver on it, against the dense Jacobian and a dense LU.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/core/low_rank_solver.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

using testing::case_path;
using testing::load_spec;
using testing::random_state;

struct Setup {
  std::string name, params;
  Escapement escapement;
};

void PrintTo(const Setup& s, std::ostream* os) {
  *os << s.name << " " << s.params << " " << to_string(s.escapement);
}

class LowRankSetups : public ::testing::TestWithParam<Setup> {};

// Expected: the dense df/dz from dual numbers (MetronomeModel::jacobian, itself held against
// finite differences in model_test.cpp), at random states and inside the escapement's switching
// band |th'| < eps/50 where f is steepest. The impulsive escapement's Jacobian is that of the
// piece the state lies in (the escapement torque constant there).
TEST_P(LowRankSetups, SparsePlusLowRankIsTheJacobian) {
  const MetronomeModel model(load_spec(GetParam().name, GetParam().params, GetParam().escapement));
  const int D = model.platform_directions(), N = model.metronome_count();
  auto jac = model.low_rank_structure();
  ASSERT_TRUE(jac.has_value());
  EXPECT_EQ(jac->rank(), D);
  // q' = v (D + N), each angular acceleration's own angle and velocity (2N), two per spring.
  EXPECT_EQ(jac->nonzeros(), D + 3 * N + 2 * static_cast<int>(model.spec().springs.size()));
  const ParameterValues values = model.default_parameters();
  std::mt19937 rng(5);
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::VectorXd z = random_state(model, rng);
    if (trial >= 4)
      for (int i = 0; i < N; ++i)
        z[model.angular_velocity_index(i)] = 2e-4 * (i + 1) * (trial == 4 ? 1 : -1);
    ASSERT_TRUE(model.low_rank_jacobian(0.0, z.data(), values.data(), *jac));
    const Eigen::MatrixXd dense = model.jacobian(0.0, z, values);
    EXPECT_LE((jac->dense() - dense).cwiseAbs().maxCoeff(), 1e-12 * dense.cwiseAbs().maxCoeff())
        << "trial " << trial;
    // S has no platform-acceleration rows: those are U W^T alone.
    const Eigen::MatrixXd s = jac->sparse_part();
    EXPECT_EQ(s.middleRows(D + N, D).cwiseAbs().maxCoeff(), 0.0);
  }
}

// Expected: a dense LU (Eigen) of I - gamma J with the model's dense Jacobian.
TEST_P(LowRankSetups, StructuredSolveMatchesDenseSolve) {
  const MetronomeModel model(load_spec(GetParam().name, GetParam().params, GetParam().escapement));
  const int n = model.dimension();
  auto jac = *model.low_rank_structure();
  LowRankSolver solver(jac);
  const ParameterValues values = model.default_parameters();
  std::mt19937 rng(9);
  for (double gamma : {1e-5, 1e-3, 2e-2}) {
    const Eigen::VectorXd z = random_state(model, rng);
    ASSERT_TRUE(model.low_rank_jacobian(0.0, z.data(), values.data(), jac));
    ASSERT_TRUE(solver.factor(jac, gamma));
    const Eigen::MatrixXd m =
        Eigen::MatrixXd::Identity(n, n) - gamma * model.jacobian(0.0, z, values);
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd expected = m.partialPivLu().solve(b);
    Eigen::VectorXd x = b;
    solver.solve(x.data());
    EXPECT_LE((x - expected).norm(), 1e-12 * expected.norm()) << "gamma " << gamma;
  }
}

INSTANTIATE_TEST_SUITE_P(Cases, LowRankSetups,
                         ::testing::Values(Setup{"row2", "table2", Escapement::Half},
                                           Setup{"row2", "table2", Escapement::Double},
                                           Setup{"row2", "table2", Escapement::Impulsive},
                                           Setup{"cross4", "", Escapement::Half},
                                           Setup{"cross4", "", Escapement::Double},
                                           Setup{"cross4_spring", "", Escapement::Half},
                                           Setup{"cross4_spring", "", Escapement::Double},
                                           Setup{"cross4_spring", "", Escapement::Impulsive},
                                           Setup{"many/many16", "", Escapement::Half},
                                           Setup{"many/many16", "", Escapement::Double}),
                         [](const auto& info) {
                           std::string s = info.param.name + "_" + to_string(info.param.escapement);
                           std::replace(s.begin(), s.end(), '/', '_');
                           return s;
                         });

}  // namespace
}  // namespace sympathy
