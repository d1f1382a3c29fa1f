// The branch workflow (continuation/branch_run.hpp) and what is done with its result: joining a
// backward and a forward run (branch.hpp), describing points (orbit_describer.hpp) and writing
// them (branch_output.hpp). About 600 lines in one file: the pieces are tested on one shared fold
// run (computed once, about 0.4 s) and one set of hand-made branches; split, each file would
// repeat them.
#include "sympathy/continuation/branch_run.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "tests/support/errors.hpp"
#include "tests/support/math.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

using testing::expect_mentions;
using testing::NormalForm;
using Kind = NormalForm::Kind;
using testing::kPi;

// ---------------------------------------------------------------------------------------------
// join_branches and order_events on hand-made branches: exact answers.

ContinuationPoint point(int index, double parameter, int iterations = 0) {
  ContinuationPoint p;
  p.index = index;
  p.parameter = parameter;
  p.iterations = iterations;
  return p;
}

Bifurcation event(int after_point, double arclength, double parameter) {
  Bifurcation e;
  e.after_point = after_point;
  e.arclength = arclength;
  e.parameter = parameter;  // identifies the event below
  return e;
}

std::vector<double> parameters_of(const std::vector<Bifurcation>& events) {
  std::vector<double> p;
  for (const auto& e : events) p.push_back(e.parameter);
  return p;
}

// A backward run from mu = 0.5 down to 0.3 and a forward run up to 0.7, both from the same start
// (index 0, marked by its iteration count: 99 on the backward copy, 1 on the forward one).
Branch backward_run() {
  Branch b;
  b.parameter_name = "mu";
  b.parameter = 0;
  b.points = {point(0, 0.5, 99), point(1, 0.4, 2), point(2, 0.3, 3)};
  // Between backward points 0 and 1 (0.01 from 0), and two between 1 and 2: 0.02 and 0.05 from 1
  // (the one at 0.05 lies nearer to point 2, so earlier along the joined branch).
  b.events = {event(0, 0.01, 0.45), event(1, 0.02, 0.38), event(1, 0.05, 0.35)};
  b.stop = StopReason::MinimumStep;
  b.stop_reason = "step size below the minimum: corrector diverged";
  b.rejected = {1, 2, 3, 4};
  b.flow.calls = 10;
  b.flow.steps = 100;
  b.flow.rhs_evaluations = 1000;
  b.seconds = 1.5;
  return b;
}

Branch forward_run() {
  Branch f;
  f.parameter_name = "mu";
  f.parameter = 0;
  f.state_names = {"x", "y"};
  f.points = {point(0, 0.5, 1), point(1, 0.6, 2), point(2, 0.7, 3)};
  // Found in this order, but 0.62 (0.005 from point 1) lies before 0.65 (0.01 from point 1).
  f.events = {event(0, 0.03, 0.55), event(1, 0.01, 0.65), event(1, 0.005, 0.62)};
  f.stop = StopReason::ParameterBound;
  f.stop_reason = "reached the parameter bound";
  f.rejected = {10, 20, 30, 40};
  f.flow.calls = 5;
  f.flow.steps = 50;
  f.flow.rhs_evaluations = 500;
  f.seconds = 0.25;
  f.options.lower = 0.3;
  f.options.upper = 0.7;
  f.start_values = Eigen::VectorXd::Constant(1, 0.5);
  return f;
}

// Backward points reversed with negated indices and without their copy of the start, then the
// forward ones.
TEST(JoinBranches, PointsInOrderAlongTheBranch) {
  const Branch joined = join_branches(backward_run(), forward_run());
  ASSERT_EQ(joined.points.size(), 5u);
  const std::vector<int> indices{-2, -1, 0, 1, 2};
  const std::vector<double> parameters{0.3, 0.4, 0.5, 0.6, 0.7};
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(joined.points[i].index, indices[i]);
    EXPECT_EQ(joined.points[i].parameter, parameters[i]);
  }
  EXPECT_EQ(joined.points[2].iterations, 1);  // the start is the forward run's
  EXPECT_EQ(joined.parameter_name, "mu");
  EXPECT_EQ(joined.state_names, (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(joined.options.lower, 0.3);
  EXPECT_EQ(joined.options.upper, 0.7);
  EXPECT_EQ(joined.start_values, Eigen::VectorXd::Constant(1, 0.5));
}

// An event between backward points k and k+1 lies between joined points -k and -(k+1): the
// point before it is -(k+1), and on the negative side larger arclength (from -k) comes first.
TEST(JoinBranches, EventsOrderedAlongTheBranch) {
  const Branch joined = join_branches(backward_run(), forward_run());
  ASSERT_EQ(joined.events.size(), 6u);
  EXPECT_EQ(parameters_of(joined.events),
            (std::vector<double>{0.35, 0.38, 0.45, 0.55, 0.62, 0.65}));
  const std::vector<int> after{-2, -2, -1, 0, 1, 1};
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(joined.events[i].after_point, after[i]) << i;
}

// Stop reasons, rejections, integration work and time are combined.
TEST(JoinBranches, StopReasonsAndStatisticsCombined) {
  const Branch joined = join_branches(backward_run(), forward_run());
  EXPECT_EQ(joined.stop, StopReason::ParameterBound);
  ASSERT_TRUE(joined.backward_stop.has_value());
  EXPECT_EQ(*joined.backward_stop, StopReason::MinimumStep);
  EXPECT_EQ(joined.stop_reason,
            "backward: step size below the minimum: corrector diverged; forward: reached the "
            "parameter bound");
  EXPECT_EQ(joined.rejected.corrector, 11);
  EXPECT_EQ(joined.rejected.turn, 22);
  EXPECT_EQ(joined.rejected.multipliers, 33);
  EXPECT_EQ(joined.rejected.location, 44);
  EXPECT_EQ(joined.flow.calls, 15);
  EXPECT_EQ(joined.flow.steps, 150);
  EXPECT_EQ(joined.flow.rhs_evaluations, 1500);
  EXPECT_EQ(joined.seconds, 1.75);
}

// A backward run without points (it failed at once) leaves the forward points as they are.
TEST(JoinBranches, EmptyBackwardRun) {
  Branch backward;
  backward.stop = StopReason::StartFailed;
  backward.stop_reason = "the starting orbit cannot be integrated";
  const Branch joined = join_branches(backward, forward_run());
  ASSERT_EQ(joined.points.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(joined.points[i].index, i);
  EXPECT_EQ(parameters_of(joined.events), (std::vector<double>{0.55, 0.62, 0.65}));
  ASSERT_TRUE(joined.backward_stop.has_value());
  EXPECT_EQ(*joined.backward_stop, StopReason::StartFailed);
}

// By after_point; within one interval by arclength, increasing on the non-negative side and
// decreasing on the negative side; events with equal keys keep their order (stable).
TEST(OrderEvents, ByPointThenArclength) {
  std::vector<Bifurcation> events{event(2, 0.1, 1.0),  event(-1, 0.1, 2.0), event(0, 0.3, 3.0),
                                  event(-1, 0.3, 4.0), event(0, 0.2, 5.0),  event(-3, 0.0, 6.0),
                                  event(2, 0.1, 7.0),  event(0, 0.2, 8.0)};
  order_events(events);
  EXPECT_EQ(parameters_of(events), (std::vector<double>{6.0, 4.0, 2.0, 5.0, 8.0, 3.0, 1.0, 7.0}));
}

// ---------------------------------------------------------------------------------------------
// continue_branch on the fold-of-cycles normal form: r' = r (mu + r^2 - r^4), theta' = 1. Its
// cycles are circles of radius r at mu = r^4 - r^2, with a fold at mu = -1/4 (r^2 = 1/2); the
// radius decreases monotonically along the branch, outer (stable) cycles to inner ones.

constexpr double kFoldValue = -0.25;

// The cycle relation mu = r^4 - r^2 at a point, r = |state0| (the orbit is a circle about the
// origin).
double family_parameter(const PeriodicOrbit& orbit) {
  const double r2 = orbit.state0.squaredNorm();
  return r2 * r2 - r2;
}

BranchProblem fold_problem(const OdeSystem& system, double from, double to,
                           std::optional<double> at = std::nullopt) {
  BranchProblem problem;
  problem.parameter = 0;
  problem.values = system.default_parameters();
  problem.from = from;
  problem.to = to;
  problem.at = at;
  problem.start_state = Eigen::Vector2d(1.0, 0.0);  // attracted to the outer cycle
  return problem;
}

// One group "radius", one number: the radius of the orbit's first state.
class RadiusDescriber final : public OrbitDescriber {
 public:
  std::vector<Group> layout() const override { return {{"radius", "radius_", {"r"}}}; }
  std::vector<double> describe(const PeriodicOrbit& orbit) const override {
    return {orbit.state0.norm()};
  }
};

// A run and what its callbacks saw.
struct BranchRun {
  Branch branch;
  std::vector<ContinuationPoint> points_seen;  // by on_point, in order
  std::vector<Bifurcation> events_seen;        // by on_event, in order
};

BranchRun run_branch(const OdeSystem& system, const BranchProblem& problem,
                     const OrbitDescriber* describer = nullptr) {
  BranchRun run;
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint& p) { run.points_seen.push_back(p); };
  callbacks.on_event = [&](const Bifurcation& e) { run.events_seen.push_back(e); };
  run.branch = continue_branch(system, problem, ContinuationOptions{}, callbacks, describer);
  return run;
}

// One way from the outer cycle at mu = -0.2 down through the fold and back up the inner cycles
// to the bound -0.2 (default options), described by RadiusDescriber. Shared by the tests below.
const BranchRun& one_way_run() {
  static const BranchRun run = [] {
    const NormalForm system(Kind::Fold, -0.2);
    const RadiusDescriber describer;
    return run_branch(system, fold_problem(system, -0.2, -0.3), &describer);
  }();
  return run;
}

// The start orbit at mu = -0.2 (the outer cycle, r^2 = (1 + sqrt(0.2)) / 2).
PeriodicOrbit start_orbit(const OdeSystem& system) {
  const auto values = system.with_parameter(system.default_parameters(), 0, -0.2);
  const PeriodicOrbit orbit =
      find_periodic_orbit(system, values, Eigen::Vector2d(1.0, 0.0), {}, OrbitOptions{});
  EXPECT_TRUE(orbit.converged()) << orbit.newton.reason;
  return orbit;
}

// Both ways from that orbit, at = -0.2 in from = -0.3 .. to = -0.15: forward (toward `to`) up the
// outer cycles to -0.15; backward down through the fold and up the inner cycles to -0.15.
struct TwoWay {
  PeriodicOrbit start;
  BranchRun run;
};
const TwoWay& two_way_run() {
  static const TwoWay two_way = [] {
    const NormalForm system(Kind::Fold, -0.2);
    TwoWay t;
    t.start = start_orbit(system);
    BranchProblem problem = fold_problem(system, -0.3, -0.15, -0.2);
    problem.start_orbit = t.start;
    t.run = run_branch(system, problem);
    return t;
  }();
  return two_way;
}

// The fold at mu = -1/4 exactly (see above), located to the location tolerance: relative 1e-8
// with scale max(|mu|, 1) (location.cpp), so 1e-8 here. Its orbit has r^2 = 1/2 (to 1e-4: the
// parameter is flat at a fold, the state only known to the square root of its error) and period
// 2 pi (theta' = 1) to 1e-9.
TEST(ContinueBranch, OneWayRunLocatesTheFold) {
  const Branch& branch = one_way_run().branch;
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  EXPECT_EQ(branch.stop, StopReason::ParameterBound) << branch.stop_reason;
  EXPECT_FALSE(branch.backward_stop.has_value());
  ASSERT_EQ(branch.events.size(), 1u) << branch.stop_reason;
  const Bifurcation& fold = branch.events[0];
  EXPECT_EQ(fold.type, BifurcationType::Fold);
  EXPECT_TRUE(fold.located());
  EXPECT_TRUE(fold.trusted()) << fold.note;
  const double tolerance = branch.options.location_tolerance * std::max(std::abs(kFoldValue), 1.0);
  EXPECT_NEAR(fold.parameter, kFoldValue, tolerance);
  EXPECT_NEAR(fold.state0.squaredNorm(), 0.5, 1e-4);
  EXPECT_NEAR(fold.period, 2 * kPi, 1e-9);
  // The run's bounds are from..to; indices 0, 1, ...; every point on the family mu = r^4 - r^2
  // (to 1e-8: a state accurate to about the corrector's 1e-9 residual).
  EXPECT_EQ(branch.options.lower, -0.3);
  EXPECT_EQ(branch.options.upper, -0.2);
  for (std::size_t i = 0; i < branch.points.size(); ++i) {
    const auto& p = branch.points[i];
    EXPECT_EQ(p.index, static_cast<int>(i));
    EXPECT_GE(p.parameter, -0.3);
    EXPECT_LE(p.parameter, -0.2);
    EXPECT_NEAR(p.parameter, family_parameter(p.orbit), 1e-8) << p.index;
  }
  // It ends on the inner cycles at the bound -0.2, exactly (r^2 = (1 - sqrt(0.2)) / 2).
  EXPECT_EQ(branch.points.back().parameter, -0.2);
  EXPECT_NEAR(branch.points.back().orbit.state0.squaredNorm(), (1 - std::sqrt(0.2)) / 2, 1e-8);
}

// Points in order along the branch: indices strictly increasing from negative to positive, one
// index 0, the radius strictly increasing (inner cycles, fold, outer cycles), each point on the
// family; the fold (exact -1/4, to the location tolerance 1e-8) on the backward part, between
// the two points it names, whose radii bracket sqrt(1/2).
TEST(ContinueBranch, TwoWayRunIsInOrderAlongTheBranch) {
  const Branch& branch = two_way_run().run.branch;
  ASSERT_TRUE(branch.started()) << branch.stop_reason;
  ASSERT_GE(branch.points.size(), 3u);
  EXPECT_LT(branch.points.front().index, 0);
  EXPECT_GT(branch.points.back().index, 0);
  EXPECT_EQ(std::count_if(branch.points.begin(), branch.points.end(),
                          [](const auto& p) { return p.index == 0; }),
            1);
  for (std::size_t i = 1; i < branch.points.size(); ++i) {
    EXPECT_EQ(branch.points[i].index, branch.points[i - 1].index + 1);
    EXPECT_GT(branch.points[i].orbit.state0.norm(), branch.points[i - 1].orbit.state0.norm())
        << branch.points[i].index;
  }
  for (const auto& p : branch.points) {
    EXPECT_NEAR(p.parameter, family_parameter(p.orbit), 1e-8) << p.index;
    EXPECT_GE(p.parameter, -0.3);
    EXPECT_LE(p.parameter, -0.15);
  }
  EXPECT_EQ(branch.points.front().parameter, -0.15);  // both ends on the bound -0.15
  EXPECT_EQ(branch.points.back().parameter, -0.15);
  ASSERT_TRUE(branch.backward_stop.has_value());
  EXPECT_EQ(*branch.backward_stop, StopReason::ParameterBound);
  EXPECT_EQ(branch.stop, StopReason::ParameterBound);
  EXPECT_EQ(branch.stop_reason,
            "backward: reached the parameter bound; forward: reached the parameter bound");

  ASSERT_EQ(branch.events.size(), 1u);
  const Bifurcation& fold = branch.events[0];
  EXPECT_EQ(fold.type, BifurcationType::Fold);
  EXPECT_NEAR(fold.parameter, kFoldValue, 1e-8);
  ASSERT_LT(fold.after_point, 0);
  const int before = fold.after_point - branch.points.front().index;  // position in points
  ASSERT_GE(before, 0);
  ASSERT_LT(before + 1, static_cast<int>(branch.points.size()));
  EXPECT_LT(branch.points[before].orbit.state0.squaredNorm(), 0.5);
  EXPECT_GT(branch.points[before + 1].orbit.state0.squaredNorm(), 0.5);
}

// The forward part of a two-way run is the one-way run from the same orbit, bit for bit. The
// one-way run is the Continuation a branch run makes (bounds min/max of from and to: the
// parameter's scale and the largest parameter step come from them, so a run over another
// interval, e.g. from `at` to `to`, takes other steps), in the direction of `to`.
TEST(ContinueBranch, TwoWayForwardPartIsTheOneWayRun) {
  const TwoWay& t = two_way_run();
  const NormalForm system(Kind::Fold, -0.2);
  ContinuationOptions bounded;
  bounded.lower = -0.3;
  bounded.upper = -0.15;
  Continuation continuation(system, 0, bounded);
  const Branch one_way = continuation.run(t.start, +1);

  std::vector<const ContinuationPoint*> forward;
  for (const auto& p : t.run.branch.points)
    if (p.index >= 0) forward.push_back(&p);
  ASSERT_EQ(forward.size(), one_way.points.size());
  for (std::size_t i = 0; i < forward.size(); ++i) {
    const ContinuationPoint& a = *forward[i];
    const ContinuationPoint& b = one_way.points[i];
    SCOPED_TRACE(b.index);
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.parameter, b.parameter);
    EXPECT_EQ(a.unknowns, b.unknowns);
    EXPECT_EQ(a.tangent, b.tangent);
    EXPECT_EQ(a.step, b.step);
    EXPECT_EQ(a.iterations, b.iterations);
    EXPECT_EQ(a.orbit.state0, b.orbit.state0);
    EXPECT_EQ(a.orbit.period, b.orbit.period);
    EXPECT_EQ(a.orbit.residual, b.orbit.residual);
    ASSERT_EQ(a.orbit.floquet.multipliers.size(), b.orbit.floquet.multipliers.size());
    for (std::size_t k = 0; k < a.orbit.floquet.multipliers.size(); ++k)
      EXPECT_EQ(a.orbit.floquet.multipliers[k].value, b.orbit.floquet.multipliers[k].value);
  }
  EXPECT_EQ(t.run.branch.stop, one_way.stop);
}

// Callbacks see the joined branch as it is built: each of its points once, with its index along
// the joined branch (the start, index 0, once: it is the forward run's and the backward run's
// first point, but one point of the branch), and each event with the point before it along the
// joined branch (the fold here is on the backward part: after_point negative).
TEST(ContinueBranch, TwoWayCallbacksSeeTheJoinedBranch) {
  const BranchRun& run = two_way_run().run;
  std::vector<int> seen, branch;
  for (const auto& p : run.points_seen) seen.push_back(p.index);
  for (const auto& p : run.branch.points) branch.push_back(p.index);
  EXPECT_EQ(std::count(seen.begin(), seen.end(), 0), 1)
      << "the start reached on_point more than once";
  EXPECT_EQ(seen.size(), branch.size());
  std::sort(seen.begin(), seen.end());
  EXPECT_EQ(seen, branch);
  // Events reach on_event as they are located (forward ones first); each is found in the branch
  // by its value.
  ASSERT_EQ(run.events_seen.size(), run.branch.events.size());
  for (const auto& e : run.events_seen) {
    const auto in_branch = std::find_if(run.branch.events.begin(), run.branch.events.end(),
                                        [&](const auto& b) { return b.parameter == e.parameter; });
    ASSERT_NE(in_branch, run.branch.events.end()) << e.parameter;
    EXPECT_EQ(e.after_point, in_branch->after_point) << "event at " << e.parameter;
  }
}

// A stop request after 3 points: the forward run is interrupted with them, and no backward run
// follows.
TEST(ContinueBranch, InterruptedRunHasNoBackwardPart) {
  const NormalForm system(Kind::Fold, -0.2);
  BranchProblem problem = fold_problem(system, -0.3, -0.15, -0.2);
  int points = 0;
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint&) { ++points; };
  callbacks.stop_requested = [&] { return points >= 3; };
  const Branch branch = continue_branch(system, problem, ContinuationOptions{}, callbacks);
  EXPECT_EQ(branch.stop, StopReason::Interrupted) << branch.stop_reason;
  EXPECT_EQ(branch.stop_reason, "interrupted");
  EXPECT_FALSE(branch.backward_stop.has_value());
  EXPECT_EQ(points, 3);
  ASSERT_EQ(branch.points.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(branch.points[i].index, i);
}

// Every point is described (the describer's number: the radius, computed from the same orbit, so
// equal exactly), both in the branch and as on_point sees it.
TEST(ContinueBranch, DescribesEveryPoint) {
  const BranchRun& run = one_way_run();
  ASSERT_FALSE(run.branch.points.empty());
  for (const auto& p : run.branch.points)
    EXPECT_EQ(p.description, std::vector<double>{p.orbit.state0.norm()}) << p.index;
  ASSERT_EQ(run.points_seen.size(), run.branch.points.size());
  for (std::size_t i = 0; i < run.points_seen.size(); ++i) {
    EXPECT_EQ(run.points_seen[i].index, run.branch.points[i].index);
    EXPECT_EQ(run.points_seen[i].description, run.branch.points[i].description);
  }
}

// ---------------------------------------------------------------------------------------------
// BranchProblem::problem_with names the field; continue_branch refuses before any work.

TEST(BranchProblem, ValidProblemHasNoProblem) {
  const NormalForm system(Kind::Fold, -0.2);
  EXPECT_EQ(fold_problem(system, -0.2, -0.3).problem_with(system), "");
  EXPECT_EQ(fold_problem(system, -0.3, -0.15, -0.2).problem_with(system), "");
}

TEST(BranchProblem, EachWrongFieldIsNamed) {
  const NormalForm system(Kind::Fold, -0.2);
  struct Case {
    std::string field;  // what the message must begin with
    std::function<void(BranchProblem&)> spoil;
  };
  PeriodicOrbit unconverged;
  unconverged.parameters = system.default_parameters();
  const std::vector<Case> cases{
      {"parameter", [](BranchProblem& p) { p.parameter = 3; }},  // it has mu, a and omega
      {"parameter", [](BranchProblem& p) { p.parameter = -1; }},
      {"values", [](BranchProblem& p) { p.values = Eigen::VectorXd::Zero(2); }},  // not 3
      {"from, to", [](BranchProblem& p) { p.to = p.from; }},
      {"from, to", [](BranchProblem& p) { p.from = std::nan(""); }},
      {"at", [](BranchProblem& p) { p.at = -0.5; }},    // outside from..to
      {"at", [](BranchProblem& p) { p.at = p.from; }},  // not strictly inside
      {"start_state", [](BranchProblem& p) { p.start_state = Eigen::Vector3d(1.0, 0.0, 0.0); }},
      {"start_state", [](BranchProblem& p) { p.start_state = Eigen::VectorXd(); }},
      {"start_orbit", [&](BranchProblem& p) { p.start_orbit = unconverged; }},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.field);
    BranchProblem problem = fold_problem(system, -0.3, -0.15);
    c.spoil(problem);
    const std::string message = problem.problem_with(system);
    EXPECT_EQ(message.rfind(c.field, 0), 0u) << message;
    EXPECT_NE(message.find("expected"), std::string::npos) << message;

    int calls = 0;
    ContinuationCallbacks callbacks;
    callbacks.on_point = [&](const ContinuationPoint&) { ++calls; };
    callbacks.stop_requested = [&] {
      ++calls;
      return false;
    };
    try {
      continue_branch(system, problem, ContinuationOptions{}, callbacks);
      ADD_FAILURE() << "no std::invalid_argument";
    } catch (const std::invalid_argument& e) {
      expect_mentions(e.what(), {message});
    }
    EXPECT_EQ(calls, 0);
  }
}

// A start orbit is "a converged orbit at the first value" (branch_run.hpp): one at another value
// of the continued parameter would start the branch elsewhere (here below `from`, outside the
// interval asked for) and must be refused, naming start_orbit.
TEST(BranchProblem, StartOrbitAtAnotherValueIsNamed) {
  const NormalForm system(Kind::Fold, -0.2);
  BranchProblem problem = fold_problem(system, -0.15, -0.18);  // first value -0.15
  problem.start_orbit = start_orbit(system);                   // at -0.2
  const std::string message = problem.problem_with(system);
  EXPECT_EQ(message.rfind("start_orbit", 0), 0u) << "'" << message << "'";
}

// ---------------------------------------------------------------------------------------------
// Writers with a describer.

// A CSV line split at commas (the branch CSV quotes nothing: numbers and words).
std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream in(line);
  for (std::string f; std::getline(in, f, ',');) fields.push_back(f);
  return fields;
}

double number(const std::string& field) {
  double v = 0.0;
  const auto [end, ec] = std::from_chars(field.data(), field.data() + field.size(), v);
  EXPECT_TRUE(ec == std::errc() && end == field.data() + field.size()) << field;
  return v;
}

// The header: the fixed columns, the describer's (csv_prefix + label), the multipliers (re, im)
// and the state; one row per point, its numbers in the shortest representation that reads back
// to the same double, so they compare exactly. (read_csv, for recordings, takes numbers only,
// and the stability column holds words: the file is split here.)
TEST(BranchOutput, CsvHasTheDescribersColumns) {
  const Branch& branch = one_way_run().branch;
  const NormalForm system(Kind::Fold, -0.2);
  const RadiusDescriber describer;
  const auto path =
      (std::filesystem::temp_directory_path() / "sympathy_branch_run_test.csv").string();
  {
    BranchCsvWriter csv(path, system, "mu", &describer);
    for (const auto& p : branch.points) csv.write(p);
    csv.close();
  }
  std::ifstream in(path);
  std::vector<std::vector<std::string>> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(split(line));
  std::filesystem::remove(path);
  ASSERT_EQ(lines.size(), branch.points.size() + 1);
  const std::vector<std::string> header{"index",
                                        "mu",
                                        "period",
                                        "frequency",
                                        "stability",
                                        "unstable_count",
                                        "max_modulus",
                                        "trivial_multiplier_error",
                                        "residual",
                                        "structural",
                                        "iterations",
                                        "step",
                                        "radius_r",
                                        "mu1_re",
                                        "mu1_im",
                                        "mu2_re",
                                        "mu2_im",
                                        "x",
                                        "y"};
  EXPECT_EQ(lines[0], header);
  for (std::size_t i = 0; i < branch.points.size(); ++i) {
    const auto& p = branch.points[i];
    const auto& row = lines[i + 1];
    ASSERT_EQ(row.size(), header.size()) << i;
    EXPECT_EQ(row[0], std::to_string(p.index));
    EXPECT_EQ(number(row[1]), p.parameter);
    EXPECT_EQ(number(row[2]), p.orbit.period);
    EXPECT_EQ(row[4], to_string(p.orbit.floquet.stability));
    EXPECT_EQ(number(row[12]), p.description.at(0));
    EXPECT_EQ(number(row[13]), p.orbit.floquet.multipliers.at(0).value.real());
    EXPECT_EQ(number(row[17]), p.orbit.state0[0]);
    EXPECT_EQ(number(row[18]), p.orbit.state0[1]);
  }
}

// JSON: the describer's group as a list per point, the events with "located" and "location";
// through write_json and back, every number is the same double.
TEST(BranchOutput, JsonHasGroupsAndEvents) {
  const Branch& branch = one_way_run().branch;
  const RadiusDescriber describer;
  const nlohmann::json j = branch_json(branch, &describer);
  ASSERT_EQ(j["points"].size(), branch.points.size());
  for (std::size_t i = 0; i < branch.points.size(); ++i) {
    const auto& q = j["points"][i];
    EXPECT_EQ(q["index"].get<int>(), branch.points[i].index);
    ASSERT_TRUE(q["radius"].is_array());
    ASSERT_EQ(q["radius"].size(), 1u);
    EXPECT_EQ(q["radius"][0].get<double>(), branch.points[i].description.at(0));
  }
  ASSERT_EQ(j["events"].size(), 1u);
  const auto& e = j["events"][0];
  EXPECT_EQ(e["type"], "LP");
  EXPECT_EQ(e["located"], true);
  EXPECT_EQ(e["location"], "located");
  EXPECT_EQ(e["value"].get<double>(), branch.events[0].parameter);
  EXPECT_EQ(j["stop"], "parameter bound");

  const auto path =
      (std::filesystem::temp_directory_path() / "sympathy_branch_run_test.json").string();
  write_json(path, j);
  std::ifstream in(path);
  const nlohmann::json back = nlohmann::json::parse(in);
  std::filesystem::remove(path);
  EXPECT_EQ(back, j);
  EXPECT_EQ(back["events"][0]["value"].get<double>(), branch.events[0].parameter);
}

}  // namespace
}  // namespace sympathy
