// Multiple shooting's segments integrated side by side (ShootingOptions::threads).
//
// Why these are the tests: each segment is integrated from its own start by a flow restarted at
// each call, so which thread (which flow) integrates it cannot change a bit of the result; a
// thread count that did would show a flow carrying state from one call to the next, or two
// segments writing into each other's slots. The exact answers (the Hopf cycle's multipliers)
// check that the product of the segments' transitions is the monodromy whatever the threads.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <utility>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/shooting.hpp"
#include "sympathy/floquet/floquet.hpp"
#include "tests/support/cases.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::case_path;

void expect_identical(const ShootingProblem::Evaluation& a, const ShootingProblem::Evaluation& b,
                      const std::string& what) {
  EXPECT_TRUE(a.residual == b.residual) << what;
  ASSERT_EQ(a.transitions.size(), b.transitions.size()) << what;
  for (std::size_t j = 0; j < a.transitions.size(); ++j) {
    EXPECT_TRUE(a.transitions[j] == b.transitions[j]) << what << " segment " << j;
    EXPECT_TRUE(a.end_rates[j] == b.end_rates[j]) << what << " segment " << j;
  }
  EXPECT_TRUE(a.parameter_sensitivities.rows() == b.parameter_sensitivities.rows() &&
              a.parameter_sensitivities == b.parameter_sensitivities)
      << what;
  EXPECT_TRUE(a.samples.states.cols() == b.samples.states.cols() &&
              a.samples.states == b.samples.states)
      << what;
}

// Multiple shooting at the accuracy the circle's tests hold it to.
ShootingOptions on_segments(int segments) {
  ShootingOptions o;
  o.segments = segments;
  o.flow.rtol = 1e-11;
  o.flow.atol = 1e-13;
  return o;
}

// The Hopf normal form's unit circle with a transverse mode (HopfCycle): period 2 pi, multipliers
// 1, exp(-4 pi) (radial) and exp(-2 pi a) (transverse), exactly. Four segments on three threads:
// the product of the transitions has those eigenvalues, and every entry of the evaluation is
// the one-thread evaluation's to the bit.
TEST(SegmentThreads, FourSegmentsOfTheHopfCycleOnThreeThreads) {
  const testing::HopfCycle system(true, 0.5, 0.7);
  const ParameterValues p = system.default_parameters();
  ShootingOptions o = on_segments(4);
  const double T = 2.0 * std::numbers::pi;
  const Eigen::Vector3d z0(1.0, 0.0, 0.0);

  ShootingProblem one(system, o);
  const PhaseSection section = one.section_through(z0, p);
  one.record_samples(true);
  o.threads = 3;
  ShootingProblem three(system, o);
  three.record_samples(true);
  const Eigen::VectorXd x = one.unknowns_from(z0, p, T);
  ASSERT_TRUE(x == three.unknowns_from(z0, p, T));

  const auto a = one.evaluate(x, p, section, true, 0);
  const auto b = three.evaluate(x, p, section, true, 0);
  expect_identical(a, b, "with derivatives");
  EXPECT_TRUE(one.residual(x, p, section) == three.residual(x, p, section));
  EXPECT_EQ(one.statistics().steps, three.statistics().steps);
  EXPECT_EQ(one.statistics().calls, three.statistics().calls);

  // The orbit is the unit circle: the residual is the integration's error (about rtol).
  EXPECT_LT(b.residual.cwiseAbs().maxCoeff(), 1e-9);
  Eigen::MatrixXd monodromy = Eigen::MatrixXd::Identity(3, 3);
  for (const auto& t : b.transitions) monodromy = t * monodromy;
  Eigen::VectorXd mu = Eigen::EigenSolver<Eigen::MatrixXd>(monodromy).eigenvalues().real();
  std::sort(mu.data(), mu.data() + mu.size());
  EXPECT_NEAR(mu[0], std::exp(-4.0 * std::numbers::pi), 1e-9);
  EXPECT_NEAR(mu[1], std::exp(-2.0 * std::numbers::pi * 0.5), 1e-9);
  EXPECT_NEAR(mu[2], 1.0, 1e-9);
  // The samples of all four segments, 801 in all, lie on the circle at angle 2 pi k / 800.
  ASSERT_EQ(b.samples.states.cols(), PeriodSamples::intervals + 1);
  for (int k = 0; k <= PeriodSamples::intervals; k += 50) {
    const double angle = T * k / PeriodSamples::intervals;
    EXPECT_NEAR(b.samples.states(0, k), std::cos(angle), 1e-9) << k;
    EXPECT_NEAR(b.samples.states(1, k), std::sin(angle), 1e-9) << k;
  }
}

// The row setup (Table II, the whole state) in three segments, with each integrator the presets
// use: two threads (and more threads than segments) give the one-thread evaluation to the bit,
// with derivatives and a parameter column, and the plain residual too.
TEST(SegmentThreads, RowSetupSegmentsAreTheSameOnAnyNumberOfThreads) {
  const CaseFile file = CaseFile::load(case_path("row2"));
  const MetronomeModel model(file.spec());
  const ParameterValues p = model.default_parameters();
  const int k = model.parameter_index("k");
  const Eigen::VectorXd z0 = file.initial_state(&file.start("in-phase"));
  struct Integrator {
    const char* name;
    Method method;
    Sensitivities sensitivities;
    NonlinearSolver solver;
    double rtol;
  };
  for (const Integrator& i :
       {Integrator{"BDF, forward module", Method::BDF, Sensitivities::ForwardModule,
                   NonlinearSolver::Newton, 1e-9},
        Integrator{"Adams, augmented", Method::Adams, Sensitivities::Augmented,
                   NonlinearSolver::FixedPoint, 1e-10},
        Integrator{"Dormand-Prince", Method::ERK, Sensitivities::Augmented,
                   NonlinearSolver::FixedPoint, 1e-8}}) {
    ShootingOptions o;
    o.segments = 3;
    o.flow.method = i.method;
    o.flow.sensitivities = i.sensitivities;
    o.flow.nonlinear_solver = i.solver;
    o.flow.rtol = i.rtol;
    o.flow.atol = i.rtol * 1e-2;
    ShootingProblem one(model, o);
    const PhaseSection section = one.section_through(z0, p);
    one.record_samples(true);
    const Eigen::VectorXd x = one.unknowns_from(z0, p, 0.58);
    one.reset_statistics();
    const auto a = one.evaluate(x, p, section, true, k);
    const Eigen::VectorXd r = one.residual(x, p, section);
    const long steps = one.statistics().steps;
    for (int threads : {2, 5}) {
      o.threads = threads;
      ShootingProblem many(model, o);
      many.record_samples(true);
      const std::string what = std::string(i.name) + ", " + std::to_string(threads) + " threads";
      expect_identical(a, many.evaluate(x, p, section, true, k), what);
      EXPECT_TRUE(r == many.residual(x, p, section)) << what;
      // Every flow's work is counted, the helpers' too.
      EXPECT_EQ(many.statistics().steps, steps) << what;
    }
  }
}

// A failing segment: the error is the first failing segment's, as one thread would report it,
// though a later segment on another thread failed too (z' = z^2 from z blows up at t = 1/z).
TEST(SegmentThreads, TheFirstFailingSegmentsErrorIsRethrown) {
  const testing::BlowUp system;
  const ParameterValues p = system.default_parameters();
  ShootingOptions o;
  o.segments = 3;
  o.flow.max_steps = 2000;
  // Period 3: each segment runs for 1. Segments 1 and 2 start at 2 and 4, so they blow up at
  // t = 0.5 and 0.25 (segment 0, from 0.1, does not).
  Eigen::VectorXd x(4);
  x << 0.1, 2.0, 4.0, 3.0;
  // The error (its message and the time it was raised at) of one evaluation on `threads`.
  const auto failure = [&](int threads) {
    o.threads = threads;
    ShootingProblem problem(system, o);
    try {
      problem.evaluate(x, p, {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Ones(1)}, true);
    } catch (const IntegrationError& e) {
      return std::pair<std::string, double>(e.what(), e.time());
    }
    return std::pair<std::string, double>("", 0.0);
  };
  const auto alone = failure(1);
  const auto beside = failure(3);
  ASSERT_FALSE(alone.first.empty()) << "segment 1 must fail";
  // Segment 1's blow-up (at t = 0.5), not segment 2's (at 0.25).
  EXPECT_GT(alone.second, 0.4);
  EXPECT_LE(alone.second, 0.5);
  EXPECT_EQ(alone.first, beside.first);
  EXPECT_EQ(alone.second, beside.second);
}

// A refinement's re-sampling (unknowns_from_starts): on the unit circle, 8 segments' starts from
// the starts of 2 lie at angles 2 pi j / 8 (each integrated over one segment from the one before,
// from the latest given start on), to the integration's error; the given starts are kept to the
// bit; starts that do not divide the segments are refused.
TEST(SegmentThreads, RefinedStartsFromTheCoarseOnes) {
  const testing::HopfCycle system;
  const ParameterValues p = system.default_parameters();
  const ShootingOptions o = on_segments(8);
  const double T = 2.0 * std::numbers::pi;
  ShootingProblem problem(system, o);
  Eigen::MatrixXd coarse(2, 2);
  coarse << 1.0, -1.0, 0.0, 0.0;  // angles 0 and pi
  const Eigen::VectorXd x = problem.unknowns_from_starts(coarse, p, T);
  ASSERT_EQ(x.size(), 8 * 2 + 1);
  for (int j = 0; j < 8; ++j) {
    const double angle = T * j / 8;
    EXPECT_NEAR(x[2 * j], std::cos(angle), 1e-9) << j;
    EXPECT_NEAR(x[2 * j + 1], std::sin(angle), 1e-9) << j;
  }
  EXPECT_TRUE(x.segment(8, 2) == coarse.col(1));
  EXPECT_EQ(x[16], T);
  EXPECT_THROW(problem.unknowns_from_starts(Eigen::MatrixXd::Zero(2, 3), p, T),
               std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
