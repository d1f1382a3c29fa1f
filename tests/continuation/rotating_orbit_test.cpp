// States declared as angles (OdeSystem::angle_states): a pendulum driven by a constant torque
// rotates, its angle gaining 2 pi per period; the orbit is found, continued and checked against
// the balance of energy and Liouville's formula.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <numbers>

#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/continuation/recorded_period.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "tests/support/math.hpp"

namespace sympathy {
namespace {

using testing::kTwoPi;
using testing::nontrivial_multiplier;

// theta'' + gamma theta' + sin(theta) = tau, states theta (an angle, if `declared`) and omega.
// With tau > 1 there is no equilibrium and every motion ends on the rotation. Over its period:
//   energy: the torque's work equals what damping takes, tau 2 pi = gamma int omega^2 dt (the
//     pendulum's energy omega^2 / 2 - cos(theta) is back where it was);
//   Liouville: the multipliers' product is exp(int div f dt) = exp(-gamma T), and one of them
//     is the trivial 1, so the other is exp(-gamma T).
class DrivenPendulum final : public AutoDiffSystem<DrivenPendulum> {
 public:
  DrivenPendulum(double gamma, double tau, bool declared = true) : declared_(declared) {
    set_parameter_layout({{"gamma", {0}}, {"tau", {1}}}, {gamma, tau});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"theta", "omega"}; }
  std::vector<int> angle_states() const override {
    return declared_ ? std::vector<int>{0} : std::vector<int>{};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    using std::sin;
    dz[0] = z[1];
    dz[1] = p[1] - p[0] * z[1] - sin(z[0]);
  }

 private:
  bool declared_;
};

// gamma int_0^T omega^2 dt by Simpson's rule on 4000 intervals of the orbit, integrated at rtol
// 1e-12: the rule's error is about (T / 4000)^4 |omega''''| ~ 1e-13 here.
double dissipated(const OdeSystem& system, const PeriodicOrbit& orbit) {
  FlowOptions accurate;
  accurate.rtol = 1e-12;
  accurate.atol = 1e-14;
  Flow flow(system, accurate);
  const int intervals = 4000;
  std::vector<double> times;
  for (int k = 1; k <= intervals; ++k) times.push_back(orbit.period * k / intervals);
  double sum = orbit.state0[1] * orbit.state0[1];  // the weight-1 end at t = 0
  int k = 0;
  flow.sample(orbit.state0, orbit.parameters, 0.0, times, [&](double, const Eigen::VectorXd& z) {
    ++k;
    const double w = k == intervals ? 1.0 : (k % 2 ? 4.0 : 2.0);
    sum += w * z[1] * z[1];
  });
  const double gamma = system.parameter(orbit.parameters, 0);
  return gamma * sum * orbit.period / intervals / 3.0;
}

// gamma = 0.5, tau = 1.2: the rotation from a start at rest, found by the transient and Newton.
// Energy balance and Liouville to 1e-8 relative (the orbit at rtol 1e-11); after one period the
// angle has gained 2 pi and the velocity is back, to 1e-8.
TEST(RotatingOrbit, DrivenPendulumRotationBalancesItsEnergy) {
  const DrivenPendulum system(0.5, 1.2);
  const PeriodicOrbit orbit =
      find_periodic_orbit(system, system.default_parameters(), Eigen::Vector2d(0.0, 0.0),
                          InvariantSubspace(), OrbitOptions());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_NEAR(dissipated(system, orbit), kTwoPi * 1.2, kTwoPi * 1.2 * 1e-8);
  EXPECT_NEAR(nontrivial_multiplier(orbit.floquet), std::exp(-0.5 * orbit.period), 1e-8);
  EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
  EXPECT_LE(std::abs(orbit.state0[0]), std::numbers::pi);  // the transient's angle wrapped
  Flow flow(system, OrbitOptions().shooting.flow);
  const Eigen::VectorXd later = flow.advance(orbit.state0, orbit.parameters, 0.0, orbit.period);
  EXPECT_NEAR(later[0] - orbit.state0[0], kTwoPi, 1e-8);
  EXPECT_NEAR(later[1], orbit.state0[1], 1e-8);
}

// Undeclared, the same motion is no periodic orbit: no return to the section is found.
TEST(RotatingOrbit, UndeclaredAngleFindsNoOrbit) {
  const DrivenPendulum system(0.5, 1.2, false);
  const PeriodicOrbit orbit =
      find_periodic_orbit(system, system.default_parameters(), Eigen::Vector2d(0.0, 0.0),
                          InvariantSubspace(), OrbitOptions());
  EXPECT_FALSE(orbit.converged());
}

// The rotation continued in tau from 1.2 to 2 with a user point at 1.5: at every point and at
// the user point the energy balance and Liouville's multiplier hold to 1e-8.
TEST(RotatingOrbit, ContinuedInTheTorque) {
  const DrivenPendulum system(0.5, 1.2);
  BranchProblem problem;
  problem.parameter = 1;
  problem.values = system.default_parameters();
  problem.from = 1.2;
  problem.to = 2.0;
  problem.start_state = Eigen::Vector2d(0.0, 0.0);
  ContinuationOptions options;
  options.user_points = {1.5};
  const Branch branch = continue_branch(system, problem, options);
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  EXPECT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
  ASSERT_GE(branch.points.size(), 5u);
  for (const auto& p : branch.points) {
    SCOPED_TRACE("tau = " + std::to_string(p.parameter));
    EXPECT_NEAR(dissipated(system, p.orbit), kTwoPi * p.parameter, kTwoPi * p.parameter * 1e-8);
    EXPECT_NEAR(nontrivial_multiplier(p.orbit.floquet), std::exp(-0.5 * p.orbit.period), 1e-8);
  }
  ASSERT_EQ(branch.events.size(), 1u);
  EXPECT_EQ(branch.events[0].type, BifurcationType::UserPoint);
  EXPECT_NEAR(branch.events[0].parameter, 1.5, 1e-12);
}

// One and a half turns recorded from the rotation (the angle running on past 2 pi, as simulate
// writes it) and read back with theta declared an angle: the guess is the first return, found on
// the circle, and Newton gives the same orbit, state and period to 1e-9 (both converged to
// 2e-10 from the same section).
TEST(RotatingOrbit, RecordedRotationReadsBack) {
  const DrivenPendulum system(0.5, 1.2);
  const PeriodicOrbit orbit =
      find_periodic_orbit(system, system.default_parameters(), Eigen::Vector2d(0.0, 0.0),
                          InvariantSubspace(), OrbitOptions());
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  const auto dir = std::filesystem::temp_directory_path() / "sympathy_rotating_orbit";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "rotation.csv").string();
  {
    CsvWriter csv(path, {"t", "theta", "omega"});
    FlowOptions accurate;
    accurate.rtol = 1e-12;
    accurate.atol = 1e-14;
    Flow flow(system, accurate);
    std::vector<double> times;
    for (int k = 0; k <= 150; ++k) times.push_back(orbit.period * k / 100);
    flow.sample(orbit.state0, orbit.parameters, 0.0, times,
                [&](double t, const Eigen::VectorXd& z) {
                  csv.row({t, z[0], z[1]});
                });
    csv.close();
  }
  EXPECT_THROW(read_recorded_period(path, system.state_names()), InputError);  // not closed
  const RecordedPeriod r = read_recorded_period(path, system.state_names(), "the pendulum", {0});
  EXPECT_TRUE(r.returned);
  EXPECT_NEAR(r.period, orbit.period, 1e-3);
  const PeriodicOrbit again =
      orbit_from_recorded_period(system, orbit.parameters, r, InvariantSubspace(), OrbitOptions());
  ASSERT_TRUE(again.converged()) << again.newton.reason;
  EXPECT_LT((again.state0 - orbit.state0).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_NEAR(again.period, orbit.period, 1e-9);
}

}  // namespace
}  // namespace sympathy
