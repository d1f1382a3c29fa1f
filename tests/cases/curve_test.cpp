// Two-parameter curves on the row setup (Table II): the anti-phase orbit's BP curve in (k, c) and
// its first NS curve in (k, M) pass through the points a separate one-parameter continuation in k
// locates at another c and another M, within the two reported uncertainties and to 1e-7
// relative (the requirement; the one-parameter location is good to 1e-8 relative, the
// curve's points to about 2e-9 in k). The curves end on their window's edge, where the second
// parameter is exactly the value the one-parameter branch is run at.
#include <gtest/gtest.h>

#include <cmath>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/branch_run.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

const Bifurcation* first_of(const Branch& b, BifurcationType type) {
  for (const auto& e : b.events)
    if (e.type == type) return &e;
  return nullptr;
}

// The command line's default integrator (Adams on the augmented system, rtol 5e-12): about
// twice as fast as the library's BDF default at the same accuracy (bench section (f)).
OrbitOptions adams() {
  OrbitOptions o;
  FlowOptions& f = o.shooting.flow;
  f.method = Method::Adams;
  f.nonlinear_solver = NonlinearSolver::FixedPoint;
  f.sensitivities = Sensitivities::Augmented;
  f.rtol = 5e-12;
  f.atol = 5e-14;
  return o;
}

Branch anti_phase_k(const CaseFile& file, const MetronomeModel& model, ParameterValues values,
                    double from, double to) {
  BranchProblem problem = testing::branch_problem(file, model, "anti-phase", "k", to);
  problem.values = std::move(values);
  problem.from = from;
  ContinuationOptions o;
  o.orbit = adams();
  return continue_branch(model, problem, o);
}

TEST(RowCurves, AntiPhaseBranchPointAndNeimarkSackerCurvesMeetTheOneParameterPoints) {
  const CaseFile file = CaseFile::load(testing::case_path("row2"));
  const MetronomeModel model(file.spec());
  const int k = model.parameter_index("k"), c = model.parameter_index("c"),
            m = model.parameter_index("M");
  const ParameterValues table2 = model.default_parameters();
  const Branch branch = anti_phase_k(file, model, table2, 45.0, 51.0);
  const Bifurcation* bp = first_of(branch, BifurcationType::BranchPoint);
  const Bifurcation* ns = first_of(branch, BifurcationType::NeimarkSacker);
  ASSERT_TRUE(bp && ns) << branch.stop_reason;

  struct Case {
    const Bifurcation* event;
    int second;
    double upper;  // the window's far edge in the second parameter, where the check is made
  };
  for (const Case& t : {Case{bp, c, 0.06}, Case{ns, m, 0.42}}) {
    CurveOptions o;
    o.first_lower = 40.0;
    o.first_upper = 60.0;
    o.second_lower = model.parameter(table2, t.second);
    o.second_upper = t.upper;
    o.orbit = adams();
    const BifurcationCurve curve = continue_curve(model, branch, *t.event, t.second, o);
    ASSERT_TRUE(curve.started()) << curve.stop_reason;
    const CurvePoint& end = curve.points.back();
    ASSERT_EQ(curve.stop, StopReason::ParameterBound) << curve.stop_reason;
    ASSERT_EQ(end.second, t.upper);
    for (const auto& p : curve.points) EXPECT_LT(p.floquet.trivial_error, 1e-8);

    // The one-parameter branch in k at the curve's end value of the second parameter.
    const ParameterValues there = model.with_parameter(table2, t.second, t.upper);
    const Branch check = anti_phase_k(file, model, there, end.first - 0.8, end.first + 0.8);
    const Bifurcation* e = first_of(check, t.event->type);
    ASSERT_NE(e, nullptr) << check.stop_reason;
    const double difference = std::abs(e->parameter - end.first);
    EXPECT_LT(difference, e->uncertainty + end.uncertainty)
        << to_string(t.event->type) << ": curve " << end.first << " +- " << end.uncertainty
        << ", branch " << e->parameter << " +- " << e->uncertainty;
    EXPECT_LT(difference, 1e-7 * e->parameter);
    // And it moved: the curve is not flat in k.
    EXPECT_GT(std::abs(end.first - t.event->parameter), 1e-3);
  }
  (void)k;
}

}  // namespace
}  // namespace sympathy
