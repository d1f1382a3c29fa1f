// The one driver and the one locator on problems with exact answers: a circle x^2 + p^2 = r^2
// followed in arclength (its folds at p = +-r, its points exactly on it), and scalar roots.
#include "sympathy/continuation/driver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include <Eigen/Dense>

#include "sympathy/continuation/crossing_locator.hpp"

namespace sympathy {
namespace {

struct CirclePoint {
  int index = 0;
  int iterations = 0;
  double step = 0.0;
  double angle = 0.0;  // the point (r cos angle, r sin angle): x and p
  Eigen::Vector2d tangent;
};
struct CircleEvent {
  int after_point = 0;
  double parameter = 0.0;
  bool located = false;
};

// The circle of radius r in (x, p): the arclength is r times the angle, so a step ds is exact.
// Folds (p extremal) at angle pi/2 and 3 pi/2; the window p in [lower, upper].
class Circle {
 public:
  using Point = CirclePoint;
  using Event = CircleEvent;
  double r = 2.0, lower = -10.0, upper = 10.0;
  double longest = 1e9;  // steps longer than this fail in the corrector
  int direction = 1;
  int corrections = 0;
  double locates_within = 1e9;  // events on longer steps are not located

  CirclePoint at(double angle) const {
    CirclePoint c;
    c.angle = angle;
    c.tangent = direction * Eigen::Vector2d(-std::sin(angle), std::cos(angle));
    return c;
  }
  driver::Attempt<Point> step(const Point*, const Point& a, double ds) {
    ++corrections;
    driver::Attempt<Point> t;
    if (ds > longest) {
      t.why = "too long";
      return t;
    }
    t.point = at(a.angle + direction * ds / r);
    t.point->step = ds;
    t.point->iterations = 2;
    return t;
  }
  double turn_cosine(const Point& a, const Point& b) const { return a.tangent.dot(b.tangent); }
  double parameter(const Point& p) const { return r * std::sin(p.angle); }
  bool outside(const Point& b) const { return parameter(b) < lower || parameter(b) > upper; }
  std::string edge_message(const Point&) const { return "edge"; }
  std::optional<Point> onto_edge(const Point&, const Point& b) const {
    const double bound = parameter(b) > upper ? upper : lower;
    // The nearest point of the circle with that p, on b's side of x.
    const double x = std::cos(b.angle) >= 0 ? std::sqrt(r * r - bound * bound)
                                            : -std::sqrt(r * r - bound * bound);
    Point p = at(std::atan2(bound, x));
    p.iterations = 2;
    return p;
  }
  driver::Found<Event> detect(const Point*, const Point& a, const Point& b) const {
    driver::Found<Event> f;
    if (a.tangent[1] * b.tangent[1] >= 0) return f;
    // The fold: the tangent's p component through zero, by the one locator.
    using Tag = int;
    const auto test = [](const Point& p, double, const driver::End<Tag>&, const driver::End<Tag>&) {
      return driver::Sample<Tag>{p.tangent[1], 0};
    };
    const auto probe = [&](double s, std::string&) {
      return std::optional<Point>(at(a.angle + direction * s / r));
    };
    driver::LocatorOptions o;
    o.tolerance = 1e-12;
    o.floor = 1.0;
    o.fold = true;
    const auto c = driver::locate_crossing(
        a, driver::Sample<Tag>{a.tangent[1], 0}, b, driver::Sample<Tag>{b.tangent[1], 0}, b.step,
        test, probe, [&](const Point& p) { return parameter(p); }, o);
    f.events.push_back({a.index, parameter(c.point), c.located()});
    // An event the problem cannot vouch for on a long step (an orbit's fold whose multiplier a
    // long step let pass out and back): not located, for the driver to try shorter.
    if (b.step > locates_within) {
      f.events.back().located = false;
      f.unlocated = true;
    }
    return f;
  }
  std::optional<driver::Ending> ends(const Point&, const Point&, std::vector<Event>&) const {
    return std::nullopt;
  }
  void accept(Point&) {}
};

driver::Options options() {
  driver::Options o;
  o.initial_step = 0.1;
  o.min_step = 1e-6;
  o.max_step = 0.4;
  o.max_points = 1000;
  o.min_tangent_cosine = 0.9;
  return o;
}

TEST(Driver, StopsOnTheWindowsEdgeAndLocatesTheFoldExactly) {
  Circle circle;
  // From angle 0 counter-clockwise p = 2 sin(angle) grows towards the fold at p = 2; the window's
  // edge at 1.5 comes first, and the last point lies exactly on it.
  circle.upper = 1.5;
  circle.lower = -1.9;
  auto r = driver::continuation(circle, circle.at(0.0), options());
  ASSERT_EQ(r.stop, driver::Stop::ParameterBound) << r.message;
  EXPECT_EQ(r.message, "edge");
  EXPECT_NEAR(circle.parameter(r.points.back()), 1.5, 1e-14);
  EXPECT_TRUE(r.events.empty());
  // Clockwise, p falls to the fold at p = -2 (angle -pi/2), passes it and comes back up on the
  // far side of the circle to the edge at 1.5.
  circle.lower = -3.0;
  circle.direction = -1;
  auto s = driver::continuation(circle, circle.at(0.0), options());
  ASSERT_EQ(s.stop, driver::Stop::ParameterBound);
  ASSERT_EQ(s.events.size(), 1u);
  EXPECT_TRUE(s.events[0].located);
  EXPECT_NEAR(s.events[0].parameter, -2.0, 1e-11);  // p at the fold: r exactly, to 1e-12 * r
  EXPECT_NEAR(circle.parameter(s.points.back()), 1.5, 1e-14);
  EXPECT_LT(std::cos(s.points.back().angle), 0.0);  // on the far side of the circle
  // Indices count along the branch; each event lies after the point before it.
  for (std::size_t i = 0; i < s.points.size(); ++i) EXPECT_EQ(s.points[i].index, int(i));
  EXPECT_LT(s.events[0].after_point, int(s.points.size()) - 1);
}

// A step whose event was not located is tried shorter, at most location_retries times; then the
// step is taken and the event kept, unlocated. On the circle of radius 2 from angle 0 the steps
// grow 0.1, 0.15, 0.225, 0.3375 (the fold at p = 2 lies 3.14 along): the step across it is longer
// than 0.12 and is halved until it is not (three retries are enough from at most 0.4), or, with
// one retry allowed per step, kept unlocated.
TEST(Driver, StepWithAnUnlocatedEventIsRetriedShorter) {
  for (int retries : {3, 1, 0}) {
    Circle circle;
    circle.locates_within = 0.12;
    circle.lower = -1.5;  // past the fold at p = 2, down the far side to p = -1.5
    driver::Options o = options();
    o.location_retries = retries;
    auto r = driver::continuation(circle, circle.at(0.0), o);
    ASSERT_EQ(r.stop, driver::Stop::ParameterBound) << r.message;
    ASSERT_EQ(r.events.size(), 1u) << retries;
    const int tried = r.rejected[static_cast<int>(driver::Cause::Location)];
    if (retries == 3) {
      EXPECT_TRUE(r.events[0].located);
      EXPECT_NEAR(r.events[0].parameter, 2.0, 1e-11);
      EXPECT_GE(tried, 1);
      EXPECT_LE(tried, 3);
    } else {
      // Retried at most once per step (a retry may end short of the fold: the next step tries
      // again), never with none allowed.
      EXPECT_FALSE(r.events[0].located) << retries;
      EXPECT_EQ(tried > 0, retries > 0) << retries;
    }
  }
}

TEST(Driver, StepRuleGrowsToTheMaximumAndRetriesShorterByCause) {
  Circle circle;
  circle.longest = 0.25;  // the corrector fails above: the step settles below it
  driver::Options o = options();
  o.max_points = 40;
  auto r = driver::continuation(circle, circle.at(0.0), o);
  EXPECT_EQ(r.stop, driver::Stop::PointLimit);
  EXPECT_EQ(r.points.size(), 40u);
  // 0.1 -> 0.15 -> 0.225 -> 0.3375 fails -> 0.16875, then 1.5 times again -> 0.253125 fails ...
  EXPECT_DOUBLE_EQ(r.points[1].step, 0.1);
  EXPECT_DOUBLE_EQ(r.points[2].step, 0.15);
  EXPECT_DOUBLE_EQ(r.points[3].step, 0.225);
  EXPECT_DOUBLE_EQ(r.points[4].step, 0.16875);
  EXPECT_DOUBLE_EQ(r.points[5].step, 0.253125 / 2);
  EXPECT_GT(r.rejected[static_cast<int>(driver::Cause::Corrector)], 0);
  for (const auto& p : r.points) EXPECT_LE(p.step, 0.25);
  // A tangent that turns more than allowed: a circle of radius 0.1 at steps of 0.1 turns by a
  // radian (cosine 0.54 < 0.9): halved until it does not.
  Circle tight;
  tight.r = 0.1;
  o.max_points = 5;
  auto t = driver::continuation(tight, tight.at(0.0), o);
  EXPECT_GT(t.rejected[static_cast<int>(driver::Cause::Turn)], 0);
  for (std::size_t i = 1; i < t.points.size(); ++i)
    EXPECT_GE(std::cos(t.points[i].step / 0.1), 0.9);
}

TEST(Driver, MinimumStepInterruptedAndTheJoin) {
  Circle failing;
  failing.longest = 1e-9;  // every step fails
  auto f = driver::continuation(failing, failing.at(0.0), options());
  EXPECT_EQ(f.stop, driver::Stop::MinimumStep);
  EXPECT_EQ(f.points.size(), 1u);
  EXPECT_NE(f.message.find("too long"), std::string::npos) << f.message;

  Circle circle;
  int polled = 0;
  driver::Callbacks<CirclePoint, CircleEvent> cb;
  int reported = 0;
  cb.on_progress = [&](const driver::Progress& p) { reported = p.points; };
  cb.stop_requested = [&] { return ++polled > 3; };
  auto i = driver::continuation(circle, circle.at(0.0), options(), cb);
  EXPECT_EQ(i.stop, driver::Stop::Interrupted);
  EXPECT_EQ(i.points.size(), 4u);  // the start and three steps
  EXPECT_EQ(reported, 4);

  // Both ways from angle 0 up to p = +-1.5: one branch from p = -1.5 to 1.5, indices from
  // -n to m, the start once, tangents all pointing the forward way.
  circle.upper = 1.5;
  circle.lower = -1.5;
  auto forward = driver::continuation(circle, circle.at(0.0), options());
  circle.direction = -1;
  auto backward = driver::continuation(circle, circle.at(0.0), options());
  const std::size_t n = backward.points.size(), m = forward.points.size();
  auto joined = driver::join(std::move(backward), std::move(forward));
  ASSERT_EQ(joined.points.size(), n + m - 1);
  EXPECT_EQ(joined.points.front().index, -int(n - 1));
  EXPECT_EQ(joined.points[n - 1].index, 0);
  EXPECT_NEAR(circle.parameter(joined.points.front()), -1.5, 1e-14);
  EXPECT_NEAR(circle.parameter(joined.points.back()), 1.5, 1e-14);
  for (std::size_t k = 1; k < joined.points.size(); ++k) {
    EXPECT_EQ(joined.points[k].index, joined.points[k - 1].index + 1);
    EXPECT_GT(joined.points[k].tangent[1], 0.0);  // p increases along the joined branch
  }
  EXPECT_EQ(joined.message, "backward: edge; forward: edge");
}

// The optional hooks: a screen that rejects long steps (retried at its aim, growing 1.2 after),
// and a refinement that lets the branch go on where the step fell below the minimum.
class ScreenedCircle : public Circle {
 public:
  double screen_above = 0.2;
  int refinements = 0, max_refinements = 1;
  driver::Screen screen(const Point*, const Point&, const Point& b, double ds) const {
    (void)b;
    const bool reject = ds > screen_above;
    return {reject, reject ? 0.15 : std::numeric_limits<double>::infinity(), "too fast"};
  }
  bool refine(Point&, const std::string& why) {
    if (refinements >= max_refinements) return false;
    EXPECT_EQ(why, "too long");
    ++refinements;
    longest = 1e9;  // resolved better: every step corrects again
    return true;
  }
};

TEST(Driver, ScreenAndRefinement) {
  ScreenedCircle circle;
  driver::Options o = options();
  o.max_points = 6;
  auto r = driver::continuation(circle, circle.at(0.0), o);
  // 0.1, 0.15, then 0.225 is screened (above 0.2): retried at half (below its aim 0.15), then
  // 1.2 times that.
  EXPECT_DOUBLE_EQ(r.points[1].step, 0.1);
  EXPECT_DOUBLE_EQ(r.points[2].step, 0.15);
  EXPECT_DOUBLE_EQ(r.points[3].step, 0.1125);
  EXPECT_DOUBLE_EQ(r.points[4].step, 0.1125 * 1.2);
  // ... and 1.5 times after that again: 0.2025, screened a second time.
  EXPECT_EQ(r.rejected[static_cast<int>(driver::Cause::Multipliers)], 2);

  ScreenedCircle failing;
  failing.longest = 1e-9;  // every step fails until refined
  auto f = driver::continuation(failing, failing.at(0.0), o);
  EXPECT_EQ(failing.refinements, 1);
  EXPECT_EQ(f.stop, driver::Stop::PointLimit) << f.message;  // went on from the initial step
  EXPECT_DOUBLE_EQ(f.points[1].step, 0.1);
  // A point reached by a step of 0.02 goes on from that step after its refinement, not from the
  // initial 0.1 (which on AUTO's tor jumped past a fold and a branch point side by side).
  ScreenedCircle reached;
  reached.longest = 1e-9;
  CirclePoint start = reached.at(0.0);
  start.step = 0.02;
  auto h = driver::continuation(reached, start, o);
  EXPECT_EQ(reached.refinements, 1);
  EXPECT_DOUBLE_EQ(h.points[1].step, 0.02);
  failing.max_refinements = 0;
  failing.longest = 1e-9;
  auto g = driver::continuation(failing, failing.at(0.0), o);
  EXPECT_EQ(g.stop, driver::Stop::MinimumStep);
}

TEST(Driver, OnChordWithinATenthOfItsLength) {
  // The chord from (0, 0) to (1, 0) in the plain inner product, and in one that weighs the second
  // coordinate 100 times (distances across it 10 times longer).
  const auto plain = [](const Eigen::VectorXd& u, const Eigen::VectorXd& v) { return u.dot(v); };
  const auto weighted = [](const Eigen::VectorXd& u, const Eigen::VectorXd& v) {
    return u[0] * v[0] + 100 * u[1] * v[1];
  };
  const Eigen::Vector2d a(0, 0), b(1, 0);
  EXPECT_TRUE(driver::on_chord(Eigen::Vector2d(0.5, 0.0), a, b, plain));
  EXPECT_TRUE(driver::on_chord(Eigen::Vector2d(0.3, 0.099), a, b, plain));
  EXPECT_FALSE(driver::on_chord(Eigen::Vector2d(0.3, 0.101), a, b, plain));
  EXPECT_FALSE(driver::on_chord(Eigen::Vector2d(0.3, 0.0101), a, b, weighted));
  EXPECT_TRUE(driver::on_chord(Eigen::Vector2d(1.05, 0.0), a, b, plain));   // 0.05 past b
  EXPECT_FALSE(driver::on_chord(Eigen::Vector2d(1.11, 0.0), a, b, plain));  // 0.11 past b
  EXPECT_FALSE(driver::on_chord(Eigen::Vector2d(0.0, 0.0), a, a, plain));   // no chord
}

TEST(Locator, RootOfACurvedFunctionToTheTolerance) {
  // The "branch" is the line p = s; the test s^3 - 0.3: its root 0.3^(1/3) exactly.
  using Tag = int;
  const double root = std::cbrt(0.3);
  const auto test = [](const double& p, double, const driver::End<Tag>&, const driver::End<Tag>&) {
    return driver::Sample<Tag>{p * p * p - 0.3, 0};
  };
  const auto probe = [](double s, std::string&) { return std::optional<double>(s); };
  const auto parameter = [](const double& p) { return p; };
  driver::LocatorOptions o;
  o.tolerance = 1e-12;
  o.floor = 1.0;
  const auto c =
      driver::locate_crossing(0.0, driver::Sample<Tag>{-0.3, 0}, 1.0, driver::Sample<Tag>{0.7, 0},
                              1.0, test, probe, parameter, o);
  EXPECT_TRUE(c.located());
  EXPECT_NEAR(c.point, root, 1e-12);
  EXPECT_LE(c.bracket, 1e-12);  // narrowed, or collapsed onto a probe at the root
  EXPECT_LE(c.probes, 12);      // inverse quadratic steps: superlinear

  // A test linear in s: the first secant lands on the root exactly (0.25, a binary fraction),
  // and the bracket is that probe, not the side it would have replaced (a normal form's Hopf
  // point was reported +-0.02, a whole step).
  const auto linear = [](const double& p, double, const driver::End<Tag>&,
                         const driver::End<Tag>&) {
    return driver::Sample<Tag>{p - 0.25, 0};
  };
  const auto e =
      driver::locate_crossing(0.0, driver::Sample<Tag>{-0.25, 0}, 1.0, driver::Sample<Tag>{0.75, 0},
                              1.0, linear, probe, parameter, o);
  EXPECT_TRUE(e.located());
  EXPECT_EQ(e.point, 0.25);
  EXPECT_EQ(e.bracket, 0.0);
  EXPECT_EQ(e.probes, 1);

  // A probe that fails ends the location with its reason.
  const auto failing = [](double s, std::string& why) {
    why = "no";
    return s < 0.5 ? std::optional<double>(s) : std::nullopt;
  };
  const auto d =
      driver::locate_crossing(0.0, driver::Sample<Tag>{-0.3, 0}, 1.0, driver::Sample<Tag>{0.7, 0},
                              1.0, test, failing, parameter, o);
  EXPECT_EQ(d.outcome, driver::LocatorOutcome::ProbeFailed);
  EXPECT_EQ(d.why, "no");
}

}  // namespace
}  // namespace sympathy
