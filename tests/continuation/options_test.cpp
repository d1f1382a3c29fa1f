// Options validation (core/option_check.hpp): every options struct accepts its own defaults and
// names the first field out of its domain, nested fields under their path ("orbit.shooting.flow.
// rtol"); the library refuses invalid options with std::invalid_argument naming that field,
// before any work. The domains are those stated in each validate(); one value outside each (and
// NaN for every real-valued field) is tried. Enumerations and flags have no value outside their
// domain and are not tried.
#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/flow.hpp"
#include "tests/support/errors.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::expect_mentions;
using testing::NormalForm;
using Kind = NormalForm::Kind;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A field's name and a change that takes it out of its domain.
template <class Options>
using Spoilers = std::vector<std::pair<std::string, std::function<void(Options&)>>>;

// The check names exactly `field`, says what was expected, and its message is "field: expected
// ...".
void expect_problem(const OptionCheck& check, const std::string& field) {
  ASSERT_TRUE(check.has_value()) << field << " out of its domain was accepted";
  EXPECT_EQ(check->field, field);
  EXPECT_FALSE(check->expected.empty()) << field;
  EXPECT_EQ(check->message(), field + ": expected " + check->expected);
}

const Spoilers<FlowOptions>& flow_spoilers() {
  static const Spoilers<FlowOptions> s{
      {"rtol", [](FlowOptions& o) { o.rtol = 0.0; }},
      {"rtol", [](FlowOptions& o) { o.rtol = 1e-15; }},  // below [1e-14, 1)
      {"rtol", [](FlowOptions& o) { o.rtol = 1.0; }},
      {"rtol", [](FlowOptions& o) { o.rtol = kNaN; }},
      {"atol", [](FlowOptions& o) { o.atol = 0.0; }},
      {"atol", [](FlowOptions& o) { o.atol = kNaN; }},
      {"max_steps", [](FlowOptions& o) { o.max_steps = 0; }},
      {"max_step", [](FlowOptions& o) { o.max_step = -1.0; }},
      {"max_step", [](FlowOptions& o) { o.max_step = kNaN; }},
      {"steep_step_fraction", [](FlowOptions& o) { o.steep_step_fraction = 0.7; }},  // > 2/3
      {"steep_step_fraction", [](FlowOptions& o) { o.steep_step_fraction = 0.0; }},
      {"steep_step_fraction", [](FlowOptions& o) { o.steep_step_fraction = kNaN; }},
  };
  return s;
}

const Spoilers<NewtonOptions>& newton_spoilers() {
  static const Spoilers<NewtonOptions> s{
      {"residual_tolerance", [](NewtonOptions& o) { o.residual_tolerance = 0.0; }},
      {"residual_tolerance", [](NewtonOptions& o) { o.residual_tolerance = kNaN; }},
      {"rtol_factor", [](NewtonOptions& o) { o.rtol_factor = 0.5; }},
      {"rtol_factor", [](NewtonOptions& o) { o.rtol_factor = kNaN; }},
      {"max_iterations", [](NewtonOptions& o) { o.max_iterations = 0; }},
      {"max_halvings", [](NewtonOptions& o) { o.max_halvings = -1; }},
      {"rank_tolerance", [](NewtonOptions& o) { o.rank_tolerance = 1.0; }},
      {"rank_tolerance", [](NewtonOptions& o) { o.rank_tolerance = kNaN; }},
  };
  return s;
}

const Spoilers<FloquetOptions>& floquet_spoilers() {
  static const Spoilers<FloquetOptions> s{
      {"stability_tolerance", [](FloquetOptions& o) { o.stability_tolerance = 0.0; }},
      {"stability_tolerance", [](FloquetOptions& o) { o.stability_tolerance = 1.0; }},
      {"stability_tolerance", [](FloquetOptions& o) { o.stability_tolerance = kNaN; }},
  };
  return s;
}

// ShootingOptions' own fields; its flow's come from flow_spoilers under "flow.".
const Spoilers<ShootingOptions>& shooting_spoilers() {
  static const Spoilers<ShootingOptions> s{
      {"segments", [](ShootingOptions& o) { o.segments = 0; }},
      {"segments", [](ShootingOptions& o) { o.segments = 1001; }},
      {"threads", [](ShootingOptions& o) { o.threads = 0; }},
      {"threads", [](ShootingOptions& o) { o.threads = 257; }},
  };
  return s;
}

// Every field of ShootingOptions, nested ones included, as "prefix.field".
Spoilers<ShootingOptions> all_shooting_spoilers() {
  Spoilers<ShootingOptions> all = shooting_spoilers();
  for (const auto& [field, spoil] : flow_spoilers())
    all.push_back({"flow." + field, [spoil](ShootingOptions& o) { spoil(o.flow); }});
  return all;
}

// OrbitOptions' own fields and every nested one.
Spoilers<OrbitOptions> all_orbit_spoilers() {
  Spoilers<OrbitOptions> all{
      {"transient", [](OrbitOptions& o) { o.transient = -1.0; }},
      {"transient", [](OrbitOptions& o) { o.transient = kNaN; }},
      {"max_period", [](OrbitOptions& o) { o.max_period = 0.0; }},
      {"max_period", [](OrbitOptions& o) { o.max_period = kNaN; }},
      {"early_newton_below", [](OrbitOptions& o) { o.early_newton_below = -1e-3; }},
      {"early_newton_below", [](OrbitOptions& o) { o.early_newton_below = 1.0; }},
      {"early_newton_below", [](OrbitOptions& o) { o.early_newton_below = kNaN; }},
  };
  for (const auto& [field, spoil] : all_shooting_spoilers())
    all.push_back({"shooting." + field, [spoil](OrbitOptions& o) { spoil(o.shooting); }});
  for (const auto& [field, spoil] : newton_spoilers())
    all.push_back({"newton." + field, [spoil](OrbitOptions& o) { spoil(o.newton); }});
  for (const auto& [field, spoil] : floquet_spoilers())
    all.push_back({"floquet." + field, [spoil](OrbitOptions& o) { spoil(o.floquet); }});
  for (const auto& [field, spoil] : flow_spoilers())
    all.push_back(
        {"transient_flow." + field, [spoil](OrbitOptions& o) { spoil(o.transient_flow); }});
  return all;
}

// ContinuationOptions' own fields (defaults: min_step 1e-6 <= initial_step 0.02 <= max_step 0.1)
// and every nested one under "orbit.".
Spoilers<ContinuationOptions> all_continuation_spoilers() {
  using O = ContinuationOptions;
  Spoilers<O> all{
      {"min_step", [](O& o) { o.min_step = 0.0; }},
      {"min_step", [](O& o) { o.min_step = kNaN; }},
      {"initial_step", [](O& o) { o.initial_step = 1e-7; }},  // below min_step
      {"initial_step", [](O& o) { o.initial_step = kNaN; }},
      {"max_step", [](O& o) { o.max_step = 0.01; }},  // below initial_step
      {"max_step", [](O& o) { o.max_step = kNaN; }},
      {"max_parameter_step", [](O& o) { o.max_parameter_step = -1.0; }},
      {"max_parameter_step", [](O& o) { o.max_parameter_step = kNaN; }},
      {"parameter_steps", [](O& o) { o.parameter_steps = 0.5; }},
      {"parameter_steps", [](O& o) { o.parameter_steps = kNaN; }},
      {"max_points", [](O& o) { o.max_points = 1; }},
      {"max_corrector_iterations", [](O& o) { o.max_corrector_iterations = 0; }},
      {"max_chord_steps", [](O& o) { o.max_chord_steps = -1; }},
      {"corrector_tolerance", [](O& o) { o.corrector_tolerance = 0.0; }},
      {"corrector_tolerance", [](O& o) { o.corrector_tolerance = kNaN; }},
      {"max_modulus_change", [](O& o) { o.max_modulus_change = 0.0; }},
      {"max_modulus_change", [](O& o) { o.max_modulus_change = kNaN; }},
      {"watch_band", [](O& o) { o.watch_band = -0.1; }},
      {"watch_band", [](O& o) { o.watch_band = kNaN; }},
      {"min_tangent_cosine", [](O& o) { o.min_tangent_cosine = 1.0; }},
      {"min_tangent_cosine", [](O& o) { o.min_tangent_cosine = kNaN; }},
      {"location_tolerance", [](O& o) { o.location_tolerance = 1.0; }},
      {"location_tolerance", [](O& o) { o.location_tolerance = kNaN; }},
      {"trust_limit", [](O& o) { o.trust_limit = 0.0; }},
      {"trust_limit", [](O& o) { o.trust_limit = kNaN; }},
      {"user_points", [](O& o) { o.user_points.push_back(kNaN); }},
      {"user_points", [](O& o) { o.user_points.assign(2, 0.5); }},  // repeated
  };
  for (const auto& [field, spoil] : all_orbit_spoilers())
    all.push_back({"orbit." + field, [spoil](O& o) { spoil(o.orbit); }});
  return all;
}

template <class Options>
void expect_each_field_rejected(const Spoilers<Options>& spoilers) {
  for (const auto& [field, spoil] : spoilers) {
    SCOPED_TRACE(field);
    Options options;
    spoil(options);
    expect_problem(options.validate(), field);
  }
}

TEST(OptionValidation, DefaultsAreAccepted) {
  EXPECT_FALSE(FlowOptions{}.validate().has_value());
  EXPECT_FALSE(NewtonOptions{}.validate().has_value());
  EXPECT_FALSE(FloquetOptions{}.validate().has_value());
  EXPECT_FALSE(ShootingOptions{}.validate().has_value());
  EXPECT_FALSE(OrbitOptions{}.validate().has_value());
  // The bounds (both 0 by default) are not validate()'s: a branch run sets them.
  EXPECT_FALSE(ContinuationOptions{}.validate().has_value());
}

TEST(OptionValidation, FlowOptionsNameTheField) {
  expect_each_field_rejected(flow_spoilers());
}

TEST(OptionValidation, NewtonOptionsNameTheField) {
  expect_each_field_rejected(newton_spoilers());
}

TEST(OptionValidation, FloquetOptionsNameTheField) {
  expect_each_field_rejected(floquet_spoilers());
}

TEST(OptionValidation, ShootingOptionsNameTheField) {
  expect_each_field_rejected(all_shooting_spoilers());
}

TEST(OptionValidation, OrbitOptionsNameTheField) {
  expect_each_field_rejected(all_orbit_spoilers());
}

// Every field of a continuation run, down to orbit.shooting.flow.rtol and
// orbit.transient_flow.steep_step_fraction.
TEST(OptionValidation, ContinuationOptionsNameTheField) {
  const auto spoilers = all_continuation_spoilers();
  expect_each_field_rejected(spoilers);
  // The example of the brief, spelled out.
  ContinuationOptions o;
  o.orbit.shooting.flow.rtol = 0.0;
  expect_problem(o.validate(), "orbit.shooting.flow.rtol");
}

// The first field out of its domain is the one named (validate() checks in declaration order
// and the own fields before the nested ones).
TEST(OptionValidation, FirstProblemIsNamed) {
  ContinuationOptions o;
  o.trust_limit = 0.0;
  o.orbit.transient = -1.0;
  expect_problem(o.validate(), "trust_limit");
}

// The library's entry points refuse invalid options with std::invalid_argument whose message
// names the field.
template <class F>
std::string invalid_argument_of(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << "not std::invalid_argument: " << e.what();
    return "";
  }
  ADD_FAILURE() << "no std::invalid_argument thrown";
  return "";
}

TEST(OptionEnforcement, FlowConstructor) {
  NormalForm system(Kind::Fold, -0.2);
  FlowOptions o;
  o.rtol = 0.0;
  expect_mentions(invalid_argument_of([&] { Flow flow(system, o); }), {"rtol"});
}

// Every nested field's path reaches the Continuation constructor's message.
TEST(OptionEnforcement, ContinuationConstructor) {
  NormalForm system(Kind::Fold, -0.2);
  for (const auto& [field, spoil] : all_continuation_spoilers()) {
    SCOPED_TRACE(field);
    ContinuationOptions o;
    o.lower = -0.3;
    o.upper = -0.1;
    spoil(o);
    expect_mentions(invalid_argument_of([&] { Continuation c(system, 0, o); }), {field + ":"});
  }
  // The bounds, which the Continuation checks itself.
  ContinuationOptions o;
  o.lower = o.upper = -0.2;
  expect_mentions(invalid_argument_of([&] { Continuation c(system, 0, o); }), {"upper bound"});
}

// find_periodic_orbit, for every field of OrbitOptions: the message names its path (for
// "transient_flow.rtol", not a bare "rtol" that could be the shooting flow's).
TEST(OptionEnforcement, FindPeriodicOrbit) {
  NormalForm system(Kind::Fold, -0.2);
  const Eigen::VectorXd start = Eigen::Vector2d(1.0, 0.0);
  for (const auto& [field, spoil] : all_orbit_spoilers()) {
    SCOPED_TRACE(field);
    OrbitOptions o;
    spoil(o);
    expect_mentions(invalid_argument_of([&] {
                      find_periodic_orbit(system, system.default_parameters(), start, {}, o);
                    }),
                    {field + ":"});
  }
}

TEST(OptionEnforcement, SolvePeriodicOrbit) {
  NormalForm system(Kind::Fold, -0.2);
  const Eigen::VectorXd start = Eigen::Vector2d(1.0, 0.0);
  for (const auto& [field, spoil] : all_orbit_spoilers()) {
    SCOPED_TRACE(field);
    OrbitOptions o;
    spoil(o);
    expect_mentions(invalid_argument_of([&] {
                      solve_periodic_orbit(system, system.default_parameters(), start, 6.0, {}, o);
                    }),
                    {field + ":"});
  }
}

// continue_branch refuses before any work: no point, event, stop poll or description.
TEST(OptionEnforcement, ContinueBranch) {
  NormalForm system(Kind::Fold, -0.2);
  BranchProblem problem;
  problem.parameter = 0;
  problem.values = system.default_parameters();
  problem.from = -0.2;
  problem.to = -0.3;
  problem.start_state = Eigen::Vector2d(1.0, 0.0);
  int calls = 0;
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint&) { ++calls; };
  callbacks.on_event = [&](const Bifurcation&) { ++calls; };
  callbacks.stop_requested = [&] {
    ++calls;
    return false;
  };
  for (const auto& [field, spoil] : all_continuation_spoilers()) {
    SCOPED_TRACE(field);
    ContinuationOptions o;
    spoil(o);
    expect_mentions(invalid_argument_of([&] { continue_branch(system, problem, o, callbacks); }),
                    {field + ":"});
  }
  EXPECT_EQ(calls, 0);
}

}  // namespace
}  // namespace sympathy
