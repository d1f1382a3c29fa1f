// The stiffness indicator (core/stiffness.hpp) against exact answers: the spectral radius of
// matrices with known eigenvalues, and the indicator of a harmonic oscillator beside a decaying
// mode whose rate Lambda sets the stiffness, where the non-stiff integrators' steps must come out
// set by accuracy (h rho small) for a slow mode and by their stability bounds for a fast one.
#include <gtest/gtest.h>

#include <numbers>

#include "sympathy/core/stiffness.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::LinearSystem;

using testing::kTwoPi;

// z1, z2 a harmonic oscillator of period 1 (eigenvalues +-2 pi i), and z3' = -Lambda (z3 - z1): a
// mode that relaxes at the rate Lambda onto the oscillator and follows it (the matrix is block
// triangular, so its eigenvalues are +-2 pi i and -Lambda). Slaved to z1, z3 is as smooth as the
// oscillator, so accuracy alone would allow the oscillator's steps; a decaying mode left alone
// (z3 = 0 exactly) would never be excited and would test nothing.
Eigen::MatrixXd oscillator_and_decay(double lambda) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(3, 3);
  a(0, 1) = kTwoPi;
  a(1, 0) = -kTwoPi;
  a(2, 0) = lambda;
  a(2, 2) = -lambda;
  return a;
}

FlowOptions nonstiff(Method method, double rtol) {
  FlowOptions o;
  o.method = method;
  o.nonlinear_solver =
      method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
  o.sensitivities = Sensitivities::Augmented;
  o.rtol = rtol;
  o.atol = rtol / 100.0;
  return o;
}

TEST(Stiffness, SpectralRadiusOfKnownMatrices) {
  // A damped oscillator x'' + 2 zeta w x' + w^2 x = 0 below critical damping: |lambda| = w exactly.
  const double w = 7.0, zeta = 0.3;
  Eigen::MatrixXd a(2, 2);
  a << 0.0, 1.0, -w * w, -2.0 * zeta * w;
  EXPECT_NEAR(spectral_radius(a), w, 1e-12 * w);
  EXPECT_NEAR(spectral_radius(oscillator_and_decay(1e6)), 1e6, 1e-6);
  EXPECT_NEAR(spectral_radius(oscillator_and_decay(0.1)), kTwoPi, 1e-12);
  EXPECT_EQ(spectral_radius(Eigen::MatrixXd(0, 0)), 0.0);
  EXPECT_THROW(spectral_radius(Eigen::MatrixXd::Zero(2, 3)), std::invalid_argument);
}

// A slow decay (Lambda = 1): steps set by the oscillator's accuracy, where the non-stiff methods'
// higher orders take fewer steps than BDF (indicator below 1), rho = 2 pi exactly, and the options
// stay as they are. A fast one (Lambda = 1e5, 1e5 times faster than the oscillator): the non-stiff
// integrators are held at their stability bounds (Dormand-Prince's real interval reaches h Lambda
// = 3.3; Adams-Moulton with fixed point converges while h Lambda times its leading coefficient is
// below one), so they would take at least Lambda / 4 steps where BDF takes what the oscillator
// needs: the measurement stops them at kMeasuredUpTo times BDF's, above the threshold, and BDF
// takes over, the tolerances kept.
TEST(Stiffness, IndicatorSeparatesAccuracyFromStability) {
  const Eigen::VectorXd z0 = Eigen::Vector3d(1.0, 0.0, 0.0);
  for (Method method : {Method::Adams, Method::ERK}) {
    SCOPED_TRACE(to_string(method));
    const FlowOptions o = nonstiff(method, 1e-9);
    const LinearSystem slow(oscillator_and_decay(1.0));
    const StiffnessEstimate easy =
        measure_stiffness(slow, o, z0, slow.default_parameters(), 0.0, 1.0);
    EXPECT_NEAR(easy.rate, kTwoPi, 1e-9);
    EXPECT_GT(easy.steps, 10);
    EXPECT_LT(easy.indicator, 1.0);  // measured 0.62 (Adams), 0.87 (Dormand-Prince)
    EXPECT_FALSE(easy.capped);
    EXPECT_NEAR(easy.indicator, static_cast<double>(easy.steps) / easy.bdf_steps, 1e-15);
    EXPECT_LT(easy.largest_h_rate, 0.2);
    EXPECT_EQ(after_stiffness(o, easy).method, method);

    const LinearSystem fast(oscillator_and_decay(1e5));
    const StiffnessEstimate hard =
        measure_stiffness(fast, o, z0, fast.default_parameters(), 0.0, 1.0);
    EXPECT_NEAR(hard.rate, 1e5, 1e-4);
    EXPECT_LT(hard.bdf_steps, easy.bdf_steps * 3);  // BDF: the oscillator's steps, about
    // Stability-limited, the non-stiff run would take Lambda / bound steps (30 000 to 120 000,
    // 62 to 247 times BDF's, measured uncapped); it is stopped at kMeasuredUpTo times BDF's.
    EXPECT_TRUE(hard.capped);
    EXPECT_NEAR(hard.indicator, kMeasuredUpTo, 2.0 / hard.bdf_steps);
    EXPECT_GT(hard.indicator, kStiffIndicator);
    // At the stability bounds' order: measured 0.66 (Adams, stopped while it still raises its
    // order; 2.1 over the whole period) and 4.9 (Dormand-Prince, whose error control steps past
    // its 3.3 now and then), against 0.09 and 0.04 for the slow mode.
    EXPECT_GT(hard.largest_h_rate, 0.3);
    EXPECT_LT(hard.largest_h_rate, 6.0);
    const FlowOptions chosen = after_stiffness(o, hard);
    EXPECT_EQ(chosen.method, Method::BDF);
    EXPECT_EQ(chosen.nonlinear_solver, NonlinearSolver::Newton);
    EXPECT_EQ(chosen.sensitivities, Sensitivities::ForwardModule);
    EXPECT_EQ(chosen.rtol, o.rtol);
    EXPECT_EQ(chosen.atol, o.atol);
    EXPECT_EQ(stiffness_note(hard).rfind("stiffness indicator at least ", 0), 0u);
  }
}

// Where the options already are BDF there is nothing to switch to.
TEST(Stiffness, BdfStaysBdf) {
  StiffnessEstimate e;
  e.indicator = 100.0;
  const FlowOptions bdf = nonstiff(Method::BDF, 1e-9);
  EXPECT_EQ(after_stiffness(bdf, e).method, Method::BDF);
  const LinearSystem slow(oscillator_and_decay(1.0));
  EXPECT_THROW(measure_stiffness(slow, bdf, Eigen::Vector3d(1.0, 0.0, 0.0),
                                 slow.default_parameters(), 0.0, 0.0),
               std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
