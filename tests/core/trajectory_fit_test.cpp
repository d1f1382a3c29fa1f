// The trajectory fit on a damped oscillator m x'' + c x' + k x = 0 (tests/support): recordings
// made by integrating it with known parameters, with Gaussian noise of known level added (fixed
// seed), fitted back.
#include "sympathy/core/trajectory_fit.hpp"

#include <gtest/gtest.h>

#include <random>

#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::DampedOscillator;

constexpr double kTrueC = 0.3, kTrueK = 4.0;

// x(t) of the oscillator (m = 1) from x0, v0 at the given times, integrated tightly.
Eigen::MatrixXd record(const std::vector<double>& times, double x0, double v0, double c = kTrueC,
                       double k = kTrueK) {
  DampedOscillator system(1.0, c, k);
  FlowOptions o;
  o.rtol = 1e-12;
  o.atol = 1e-14;
  Flow flow(system, o);
  Eigen::VectorXd z0(2);
  z0 << x0, v0;
  Eigen::MatrixXd values(static_cast<int>(times.size()), 1);
  int i = 0;
  flow.sample(z0, system.default_parameters(), times.front(), times,
              [&](double, const Eigen::VectorXd& z) { values(i++, 0) = z[0]; });
  return values;
}

std::vector<double> uniform_times(double t_end, double dt) {
  std::vector<double> t;
  for (int i = 0; i * dt <= t_end + 1e-12; ++i) t.push_back(i * dt);
  return t;
}

Eigen::VectorXd gaussian_noise(int n, double sigma, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  Eigen::VectorXd e(n);
  for (int i = 0; i < n; ++i) e[i] = normal(generator);
  return e;
}

// The x-recording problem with c and k free (positive, log-scaled), x(0) and v(0) from `z0`.
TrajectoryFitProblem problem(const DampedOscillator& system, const std::vector<double>& times,
                             const Eigen::MatrixXd& values, double x0, double v0) {
  TrajectoryFitProblem pb;
  pb.times = times;
  pb.observed = {0};
  pb.values = values;
  pb.initial_state = Eigen::Vector2d(x0, v0);
  pb.parameter_values = system.default_parameters();
  for (const char* name : {"c", "k"}) {
    FreeParameter f;
    f.index = system.parameter_index(name);
    f.search_lower = system.parameter(pb.parameter_values, f.index) / 10.0;
    f.search_upper = system.parameter(pb.parameter_values, f.index) * 10.0;
    pb.parameters.push_back(f);
  }
  return pb;
}

// Noise-free data, each local method from 50% and 20% off: the values to the integration's
// accuracy (fit at rtol 1e-10).
TEST(TrajectoryFit, NoiseFreeRecoveryByEachLocalMethod) {
  const auto times = uniform_times(15.0, 0.05);
  const Eigen::MatrixXd values = record(times, 1.0, 0.0);
  for (LocalMethod method : {LocalMethod::LevenbergMarquardt, LocalMethod::Slsqp,
                             LocalMethod::Lbfgs, LocalMethod::Bobyqa}) {
    DampedOscillator system(1.0, 0.45, 3.2);
    TrajectoryFitOptions o;
    o.flow.rtol = 1e-10;
    o.flow.atol = 1e-12;
    o.local = method;
    const auto r = fit_trajectory(system, problem(system, times, values, 1.0, 0.0), o);
    EXPECT_TRUE(r.converged) << to_string(method) << ": " << r.stop_reason;
    EXPECT_NEAR(r.values[0], kTrueC, 1e-7 * kTrueC) << to_string(method);
    EXPECT_NEAR(r.values[1], kTrueK, 1e-7 * kTrueK) << to_string(method);
    EXPECT_LT(std::sqrt(r.rss / r.residuals), 1e-8) << to_string(method);
    // The fitted values come back as parameter values; the system itself is only read.
    const int c = system.parameter_index("c");
    EXPECT_EQ(system.parameter(r.fitted_parameters, c), r.values[0]);
    EXPECT_EQ(system.parameter(system.default_parameters(), c), 0.45);
    EXPECT_EQ(r.start[0], 0.45);
  }
}

// Noise of level sigma: the true values within 3 standard errors, the residual RMS estimates
// sigma (to 10%, about 4 of its own standard deviations 1/sqrt(2N) at N = 400), and the standard
// errors agree with an independent computation, sigma_hat sqrt(diag((J^T J)^-1)) with J by
// central differences of plain integrations, and double with the noise.
TEST(TrajectoryFit, NoisyFitErrorBarsHoldTheTruth) {
  const auto times = uniform_times(20.0, 0.05);
  const Eigen::MatrixXd clean = record(times, 1.0, 0.0);
  const double sigma = 0.01;
  const Eigen::VectorXd noise = gaussian_noise(clean.rows(), sigma, 7);
  TrajectoryFitResult r[2];
  for (int level = 0; level < 2; ++level) {
    const Eigen::MatrixXd values = clean + (level + 1) * noise;
    DampedOscillator system(1.0, 0.4, 3.5);
    TrajectoryFitProblem pb = problem(system, times, values, values(0, 0), 0.0);
    pb.initial.push_back({0, 0.1, 0.5, 1.5});  // x(0) free: the first row is noisy too
    r[level] = fit_trajectory(system, pb, {});
    ASSERT_TRUE(r[level].converged) << r[level].stop_reason;
    const double s = (level + 1) * sigma;
    const double truth[3] = {kTrueC, kTrueK, 1.0};
    for (int j = 0; j < 3; ++j)
      EXPECT_LT(std::abs(r[level].values[j] - truth[j]), 3.0 * r[level].errors[j])
          << "unknown " << j << " at noise " << s;
    EXPECT_NEAR(r[level].column_rms[0], s, 0.1 * s);
    EXPECT_EQ(r[level].residuals, static_cast<int>(times.size()));  // x(0) free: t0 counts
  }
  for (int j = 0; j < 3; ++j) EXPECT_NEAR(r[1].errors[j] / r[0].errors[j], 2.0, 0.1) << j;

  // Independent standard errors at the first fit's optimum.
  const auto& f = r[0];
  auto trajectory = [&](double c, double k, double x0) {
    DampedOscillator system(1.0, c, k);
    FlowOptions o;
    o.rtol = 1e-12;
    o.atol = 1e-14;
    Flow flow(system, o);
    Eigen::VectorXd x(static_cast<int>(times.size()));
    int i = 0;
    flow.sample(Eigen::Vector2d(x0, 0.0), system.default_parameters(), 0.0, times,
                [&](double, const Eigen::VectorXd& z) { x[i++] = z[0]; });
    return x;
  };
  Eigen::MatrixXd J(static_cast<int>(times.size()), 3);
  for (int j = 0; j < 3; ++j) {
    Eigen::Vector3d plus = f.values, minus = f.values;
    const double h = 1e-6 * std::abs(f.values[j]);
    plus[j] += h;
    minus[j] -= h;
    J.col(j) = (trajectory(plus[0], plus[1], plus[2]) - trajectory(minus[0], minus[1], minus[2])) /
               (2.0 * h);
  }
  const Eigen::MatrixXd covariance = f.column_rms[0] * f.column_rms[0] *
                                     static_cast<double>(f.residuals) / (f.residuals - 3) *
                                     (J.transpose() * J).inverse();
  for (int j = 0; j < 3; ++j)
    EXPECT_NEAR(f.errors[j], std::sqrt(covariance(j, j)), 0.01 * f.errors[j]) << j;
}

// The stiffness alone, four times too large, over 30 cycles of a lightly damped recording: the
// sum of squares in k has a local minimum wherever the model's frequency makes the phases agree
// on average, and the local fit stops in one. The global stage (NLopt CRS2 over start/10 ..
// start*10) finds the basin of the true value and the local fit then finishes.
TEST(TrajectoryFit, GlobalStageFindsWhatLocalMisses) {
  const auto times = uniform_times(100.0, 0.05);
  const Eigen::MatrixXd values = record(times, 1.0, 0.0, 0.05, kTrueK);
  TrajectoryFitOptions o;
  o.flow.rtol = 1e-8;
  o.flow.atol = 1e-10;
  auto k_only = [&](const DampedOscillator& system) {
    TrajectoryFitProblem pb = problem(system, times, values, 1.0, 0.0);
    pb.parameters.erase(pb.parameters.begin());  // c known
    return pb;
  };
  DampedOscillator local_only(1.0, 0.05, 16.0);
  const auto local = fit_trajectory(local_only, k_only(local_only), o);
  EXPECT_GT(std::abs(local.values[0] - kTrueK), 1.0);  // somewhere else
  EXPECT_GT(local.rss, 100.0);
  o.global = GlobalMethod::ControlledRandomSearch;
  o.global_evaluations = 100;
  DampedOscillator with_global(1.0, 0.05, 16.0);
  const auto global = fit_trajectory(with_global, k_only(with_global), o);
  ASSERT_EQ(global.stages.size(), 2u);
  EXPECT_EQ(global.stages[0].name, "global");
  EXPECT_LE(global.stages[0].evaluations, 101);
  EXPECT_LT(global.stages[0].rss_end, 0.01 * global.rss_start);
  EXPECT_TRUE(global.converged) << global.stop_reason;
  EXPECT_NEAR(global.values[0], kTrueK, 1e-6 * kTrueK);
  EXPECT_LT(global.rss, 1e-8);
}

// Initial state components free as well, from wrong starts (v(0) = 0 where it was -0.8).
TEST(TrajectoryFit, FreeInitialStateIsRecovered) {
  const auto times = uniform_times(10.0, 0.05);
  const Eigen::MatrixXd values = record(times, 1.0, -0.8);
  DampedOscillator system(1.0, 0.35, 3.7);
  TrajectoryFitProblem pb = problem(system, times, values, 0.9, 0.0);
  pb.initial.push_back({0, 1.0, 0.0, 2.0});
  pb.initial.push_back({1, 1.0, -2.0, 2.0});
  TrajectoryFitOptions o;
  o.flow.rtol = 1e-10;
  o.flow.atol = 1e-12;
  const auto r = fit_trajectory(system, pb, o);
  ASSERT_TRUE(r.converged) << r.stop_reason;
  EXPECT_NEAR(r.values[0], kTrueC, 1e-7);
  EXPECT_NEAR(r.values[1], kTrueK, 1e-7);
  EXPECT_NEAR(r.values[2], 1.0, 1e-8);
  EXPECT_NEAR(r.values[3], -0.8, 1e-8);
}

// m, c and k together: only c/m and k/m show in the motion. The lost direction is reported,
// its unknowns get infinite standard errors.
TEST(TrajectoryFit, UndeterminedCombinationIsReported) {
  const auto times = uniform_times(10.0, 0.05);
  const Eigen::MatrixXd values = record(times, 1.0, 0.0);
  DampedOscillator system(1.2, 0.35, 3.7);
  TrajectoryFitProblem pb = problem(system, times, values, 1.0, 0.0);
  FreeParameter m;
  m.index = system.parameter_index("m");
  pb.parameters.push_back(m);
  const auto r = fit_trajectory(system, pb, {});
  EXPECT_EQ(r.rank, 2);
  ASSERT_EQ(r.undetermined.size(), 1u);
  EXPECT_EQ(r.undetermined[0], (std::vector<int>{0, 1, 2}));
  for (int j = 0; j < 3; ++j) EXPECT_TRUE(std::isinf(r.errors[j])) << j;
  // The combinations the data do fix are right.
  EXPECT_NEAR(r.values[0] / r.values[2], kTrueC, 1e-6);
  EXPECT_NEAR(r.values[1] / r.values[2], kTrueK, 1e-6);
}

// The first sample of a fixed initial component carries no information and is not counted;
// no more residuals than unknowns is refused.
TEST(TrajectoryFit, ResidualCountAndTooFewSamples) {
  const std::vector<double> times{0.0, 0.1, 0.2};
  const Eigen::MatrixXd values = record(times, 1.0, 0.0);
  DampedOscillator system(1.0, kTrueC, kTrueK);
  TrajectoryFitProblem pb = problem(system, times, values, 1.0, 0.0);
  EXPECT_EQ(residual_count(pb), 2);
  EXPECT_THROW(fit_trajectory(system, pb, {}), std::invalid_argument);  // 2 residuals, 2 unknowns
  pb.initial.push_back({0, 1.0, 0.0, 2.0});
  EXPECT_EQ(residual_count(pb), 3);
}

}  // namespace
}  // namespace sympathy
