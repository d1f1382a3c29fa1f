// The accuracy presets (accuracy.hpp): the library's defaults are the default preset, each preset
// sets what its table says whatever was applied before, and the names round-trip.
#include "sympathy/continuation/accuracy.hpp"

#include <gtest/gtest.h>

#include <string>

namespace sympathy {
namespace {

void expect_same_flow(const FlowOptions& a, const FlowOptions& b) {
  EXPECT_EQ(a.method, b.method);
  EXPECT_EQ(a.nonlinear_solver, b.nonlinear_solver);
  EXPECT_EQ(a.sensitivities, b.sensitivities);
  EXPECT_EQ(a.explicit_table, b.explicit_table);
  EXPECT_EQ(a.rtol, b.rtol);
  EXPECT_EQ(a.atol, b.atol);
  EXPECT_EQ(a.steep_step_fraction, b.steep_step_fraction);
}

// The library's OrbitOptions and ContinuationOptions are the command line's default: Adams with
// fixed-point iteration on the augmented system at rtol 5e-12 (atol a hundredth of it), BDF where
// the start measures stiff, the transient BDF at 1e-8.
TEST(Accuracy, TheLibrarysDefaultsAreTheDefaultPreset) {
  const OrbitOptions o;
  EXPECT_EQ(o.shooting.flow.method, Method::Adams);
  EXPECT_EQ(o.shooting.flow.nonlinear_solver, NonlinearSolver::FixedPoint);
  EXPECT_EQ(o.shooting.flow.sensitivities, Sensitivities::Augmented);
  EXPECT_EQ(o.shooting.flow.rtol, 5e-12);
  EXPECT_DOUBLE_EQ(o.shooting.flow.atol, 5e-14);
  EXPECT_TRUE(o.switch_when_stiff);
  EXPECT_EQ(o.transient_flow.method, Method::BDF);
  EXPECT_EQ(o.transient_flow.rtol, 1e-8);
  EXPECT_EQ(o.transient_flow.atol, 1e-10);

  ContinuationOptions applied;
  apply_accuracy(Accuracy::Default, applied);
  const ContinuationOptions library;
  expect_same_flow(applied.orbit.shooting.flow, library.orbit.shooting.flow);
  expect_same_flow(applied.orbit.transient_flow, library.orbit.transient_flow);
  EXPECT_EQ(applied.max_modulus_change, library.max_modulus_change);
  EXPECT_EQ(applied.parameter_steps, library.parameter_steps);
}

// Fast: Dormand-Prince at 1e-8 (its transient at 1e-6), a multiplier's modulus may move 0.05 a
// step and the parameter a tenth of the range; High: the default five times tighter.
TEST(Accuracy, EachPresetSetsItsTable) {
  ContinuationOptions fast;
  apply_accuracy(Accuracy::Fast, fast);
  EXPECT_EQ(fast.orbit.shooting.flow.method, Method::ERK);
  EXPECT_EQ(fast.orbit.shooting.flow.explicit_table, ExplicitTable::DormandPrince);
  EXPECT_EQ(fast.orbit.shooting.flow.rtol, 1e-8);
  EXPECT_EQ(fast.orbit.transient_flow.method, Method::ERK);
  EXPECT_EQ(fast.orbit.transient_flow.rtol, 1e-6);
  EXPECT_EQ(fast.max_modulus_change, 0.05);
  EXPECT_EQ(fast.parameter_steps, 10.0);

  OrbitOptions high;
  apply_accuracy(Accuracy::High, high);
  EXPECT_EQ(high.shooting.flow.method, Method::Adams);
  EXPECT_EQ(high.shooting.flow.rtol, 1e-12);
  EXPECT_DOUBLE_EQ(high.shooting.flow.atol, 1e-14);
}

// A preset applied over another gives what it gives over the library's defaults (a study file's
// `accuracy` and then the command line's --accuracy).
TEST(Accuracy, PresetsCompose) {
  for (Accuracy last : {Accuracy::Fast, Accuracy::Default, Accuracy::High}) {
    for (Accuracy first : {Accuracy::Fast, Accuracy::Default, Accuracy::High}) {
      ContinuationOptions twice, once;
      apply_accuracy(first, twice);
      apply_accuracy(last, twice);
      apply_accuracy(last, once);
      std::string trace = to_string(first);
      trace += " then ";
      trace += to_string(last);
      SCOPED_TRACE(trace);
      expect_same_flow(twice.orbit.shooting.flow, once.orbit.shooting.flow);
      expect_same_flow(twice.orbit.transient_flow, once.orbit.transient_flow);
      EXPECT_EQ(twice.orbit.switch_when_stiff, once.orbit.switch_when_stiff);
      EXPECT_EQ(twice.max_modulus_change, once.max_modulus_change);
      EXPECT_EQ(twice.parameter_steps, once.parameter_steps);
    }
  }
}

TEST(Accuracy, NamesRoundTrip) {
  for (Accuracy a : {Accuracy::Fast, Accuracy::Default, Accuracy::High})
    EXPECT_EQ(accuracy_named(to_string(a)), a);
  EXPECT_FALSE(accuracy_named("medium").has_value());
  EXPECT_FALSE(accuracy_named("Fast").has_value());
}

}  // namespace
}  // namespace sympathy
