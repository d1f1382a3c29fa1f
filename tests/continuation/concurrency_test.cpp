// Concurrent continuation runs on one model object.
//
// Why this is the test (issue: one model object must serve concurrent runs): parameter values are
// values that travel with each call (ParameterValues), never state stored in the system, so a
// const model can be shared by any number of runs at once. If any run still wrote its parameter
// into the model (or any other per-run state lived there), two runs on one object from two
// threads would see each other's values and their branches would differ from the same runs made
// one after the other. Runs are deterministic, so "the same" is bit for bit: every point's
// parameter, period, state and multipliers, and every event, compared with ==.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <latch>
#include <string>
#include <thread>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

using testing::case_path;

// A branch of the row setup (Table II) in the platform stiffness k: the orbit from `start`
// found at k = from, then continued to k = to. Everything the run computes (the start orbit
// too) reads the shared model only.
struct RowRun {
  std::string start;
  double from, to;
};

Branch run_branch(const CaseFile& file, const MetronomeModel& model, const RowRun& run) {
  const int k = model.parameter_index("k");
  const ParameterValues values = model.with_parameter(model.default_parameters(), k, run.from);
  const StartSpec& s = file.start(run.start);
  const PeriodicOrbit orbit = find_periodic_orbit(
      model, values, file.initial_state(&s), file.invariant_subspace(s, model), OrbitOptions{});
  if (!orbit.converged()) {
    Branch failed;
    failed.stop = StopReason::StartFailed;
    failed.stop_reason = "no start: " + orbit.newton.reason;
    return failed;
  }
  ContinuationOptions o;
  o.lower = std::min(run.from, run.to);
  o.upper = std::max(run.from, run.to);
  o.initial_step = 0.05;  // few points: the test is about sameness, not the branch
  o.max_step = 0.25;
  o.max_parameter_step = 0.5;
  o.max_points = 30;
  Continuation c(model, k, o);
  return c.run(orbit, run.to > run.from ? +1 : -1);
}

void expect_identical(const Branch& a, const Branch& b, const std::string& what) {
  ASSERT_TRUE(a.started()) << what << ": " << a.stop_reason;
  ASSERT_TRUE(b.started()) << what << ": " << b.stop_reason;
  EXPECT_EQ(a.stop, b.stop) << what;
  EXPECT_EQ(a.stop_reason, b.stop_reason) << what;
  ASSERT_EQ(a.points.size(), b.points.size()) << what;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    const ContinuationPoint& p = a.points[i];
    const ContinuationPoint& q = b.points[i];
    EXPECT_EQ(p.parameter, q.parameter) << what << " point " << i;
    EXPECT_EQ(p.orbit.period, q.orbit.period) << what << " point " << i;
    ASSERT_EQ(p.orbit.state0.size(), q.orbit.state0.size()) << what << " point " << i;
    EXPECT_TRUE(p.orbit.state0 == q.orbit.state0) << what << " point " << i;
    ASSERT_EQ(p.unknowns.size(), q.unknowns.size()) << what << " point " << i;
    EXPECT_TRUE(p.unknowns == q.unknowns) << what << " point " << i;
    EXPECT_TRUE(p.orbit.parameters.size() == q.orbit.parameters.size() &&
                p.orbit.parameters == q.orbit.parameters)
        << what << " point " << i;
    const auto& mu = p.orbit.floquet.multipliers;
    const auto& nu = q.orbit.floquet.multipliers;
    ASSERT_EQ(mu.size(), nu.size()) << what << " point " << i;
    for (std::size_t m = 0; m < mu.size(); ++m)
      EXPECT_EQ(mu[m].value, nu[m].value) << what << " point " << i << " multiplier " << m;
  }
  ASSERT_EQ(a.events.size(), b.events.size()) << what;
  for (std::size_t i = 0; i < a.events.size(); ++i) {
    const Bifurcation& e = a.events[i];
    const Bifurcation& f = b.events[i];
    EXPECT_EQ(e.type, f.type) << what << " event " << i;
    EXPECT_EQ(e.multiplicity, f.multiplicity) << what << " event " << i;
    EXPECT_EQ(e.parameter, f.parameter) << what << " event " << i;
    EXPECT_EQ(e.uncertainty, f.uncertainty) << what << " event " << i;
    EXPECT_EQ(e.period, f.period) << what << " event " << i;
    EXPECT_EQ(e.crossing, f.crossing) << what << " event " << i;
    ASSERT_EQ(e.state0.size(), f.state0.size()) << what << " event " << i;
    EXPECT_TRUE(e.state0 == f.state0) << what << " event " << i;
    const auto& mu = e.floquet.multipliers;
    const auto& nu = f.floquet.multipliers;
    ASSERT_EQ(mu.size(), nu.size()) << what << " event " << i;
    for (std::size_t m = 0; m < mu.size(); ++m)
      EXPECT_EQ(mu[m].value, nu[m].value) << what << " event " << i << " multiplier " << m;
    EXPECT_EQ(e.location, f.location) << what << " event " << i;
    EXPECT_EQ(e.trust, f.trust) << what << " event " << i;
    EXPECT_EQ(e.note, f.note) << what << " event " << i;
    EXPECT_EQ(e.after_point, f.after_point) << what << " event " << i;
  }
}

// Anti-phase in k from 46.8 to 47.3 (through its branch point) and in-phase from 40 to 41, first
// one after the other, then at the same time on two threads, all on one const model: the same
// branches, bit for bit. (Small ranges and long steps keep each run to about half a second.)
TEST(ConcurrentContinuation, TwoRunsOnOneModelMatchSequentialRuns) {
  const CaseFile file = CaseFile::load(case_path("row2"));
  const MetronomeModel model(file.spec("table2"));
  const RowRun a{"anti-phase", 46.8, 47.3}, b{"in-phase", 40.0, 41.0};

  const Branch sequential_a = run_branch(file, model, a);
  const Branch sequential_b = run_branch(file, model, b);
  ASSERT_GE(sequential_a.points.size(), 3u) << sequential_a.stop_reason;
  ASSERT_GE(sequential_b.points.size(), 3u) << sequential_b.stop_reason;
  // The anti-phase run crosses the branch point at k = 47.07 (tests/regression/goldens.json,
  // fig08), so that located events are compared too, not only points.
  ASSERT_FALSE(sequential_a.events.empty()) << sequential_a.stop_reason;

  const auto t0 = std::chrono::steady_clock::now();
  Branch concurrent_a, concurrent_b;
  {
    std::latch go(2);  // both runs start together, so that they overlap
    std::thread ta([&] {
      go.arrive_and_wait();
      concurrent_a = run_branch(file, model, a);
    });
    std::thread tb([&] {
      go.arrive_and_wait();
      concurrent_b = run_branch(file, model, b);
    });
    ta.join();
    tb.join();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ::testing::Test::RecordProperty("concurrent_seconds", std::to_string(seconds));

  expect_identical(sequential_a, concurrent_a, "anti-phase");
  expect_identical(sequential_b, concurrent_b, "in-phase");
}

}  // namespace
}  // namespace sympathy
