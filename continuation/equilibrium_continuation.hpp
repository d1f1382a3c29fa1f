// A branch of equilibria as the one driver's problem (driver.hpp): its unknowns Y = (x, p), the
// scaled norm, the pseudo-arclength corrector, tangents, test functions and their location
// (equilibrium_branch.hpp says what each is). Internal to the continuation layer: the branch run
// (equilibrium_branch.cpp) and the switch at a branch point (equilibrium_switching.cpp) use it.
#pragma once

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "bordered_newton.hpp"
#include "sympathy/continuation/branch_point.hpp"
#include "sympathy/continuation/crossing_locator.hpp"
#include "sympathy/continuation/driver.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/core/assignment.hpp"

namespace sympathy::detail {

using Complex = std::complex<double>;

// One way along a branch of equilibria, as the driver's problem (the pieces of the header's
// comment).
class EquilibriumContinuation {
 public:
  using Point = EquilibriumPoint;
  using Event = EquilibriumEvent;

  EquilibriumContinuation(const OdeSystem& system, int parameter, ParameterValues base,
                          const EquilibriumOptions& o)
      : system_(system),
        parameter_(parameter),
        base_(std::move(base)),
        o_(o),
        n_(system.dimension()),
        weights_(Eigen::VectorXd::Ones(n_ + 1)) {
    weights_[n_] = 1.0 / (o_.upper - o_.lower);
  }

  ParameterValues values_at(double p) const { return system_.with_parameter(base_, parameter_, p); }

  void widen_scale(const Eigen::VectorXd& x) {
    scale_ = std::max({scale_, o_.state_scale_floor, x.lpNorm<Eigen::Infinity>()});
    weights_.head(n_).setConstant(1.0 / scale_);
  }
  double dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
    return (weights_.cwiseProduct(u)).dot(weights_.cwiseProduct(v));
  }
  Eigen::VectorXd unit(const Eigen::VectorXd& u) const { return u / std::sqrt(dot(u, u)); }

  // [f_x f_p] at y = (x, p).
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& y) const {
    const ParameterValues p = values_at(y[n_]);
    Eigen::MatrixXd j(n_, n_ + 1), fx;
    system_.jacobian(0.0, y.data(), p.data(), fx);
    j.leftCols(n_) = fx;
    Eigen::VectorXd fp(n_);
    system_.parameter_derivative(0.0, y.data(), p.data(), parameter_, fp.data());
    j.col(n_) = fp;
    return j;
  }
  Eigen::VectorXd f(const Eigen::VectorXd& y) const {
    return system_.rhs(0.0, Eigen::VectorXd(y.head(n_)), values_at(y[n_]));
  }
  Eigen::MatrixXd bordered(const Eigen::MatrixXd& jac, const Eigen::VectorXd& tangent) const {
    Eigen::MatrixXd m(n_ + 1, n_ + 1);
    m.topRows(n_) = jac;
    m.row(n_) = weights_.cwiseProduct(weights_).cwiseProduct(tangent).transpose();
    return m;
  }
  // The unit tangent at y oriented along `previous`.
  Eigen::VectorXd tangent(const Eigen::MatrixXd& jac, const Eigen::VectorXd& previous) const {
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n_ + 1);
    rhs[n_] = 1.0;
    Eigen::VectorXd t = unit(bordered(jac, previous).fullPivLu().solve(rhs));
    if (dot(t, previous) < 0) t = -t;
    return t;
  }

  // Newton on f = 0 and <t, y - from> = s, from `guess`; nullopt with the reason if it fails.
  std::optional<EquilibriumPoint> correct(const Eigen::VectorXd& from, const Eigen::VectorXd& t,
                                          double s, Eigen::VectorXd y, std::string& why) const {
    const Eigen::VectorXd row = weights_.cwiseProduct(weights_).cwiseProduct(t);
    for (int it = 1; it <= o_.max_iterations; ++it) {
      const auto dy = bordered_newton_step(jacobian(y), row, f(y), row.dot(y - from) - s,
                                           "equilibrium system", why);
      if (!dy) return std::nullopt;
      y += *dy;
      const double x_size = std::max(1.0, y.head(n_).lpNorm<Eigen::Infinity>());
      const double p_size = std::max(1.0, std::abs(y[n_]));
      if (dy->head(n_).lpNorm<Eigen::Infinity>() <= o_.tolerance * x_size &&
          std::abs((*dy)[n_]) <= o_.tolerance * p_size)
        return make_point(y, t, it);
    }
    why = "Newton did not converge in " + std::to_string(o_.max_iterations) + " iterations";
    return std::nullopt;
  }

  EquilibriumPoint make_point(const Eigen::VectorXd& y, const Eigen::VectorXd& previous,
                              int iterations) const {
    EquilibriumPoint pt;
    pt.parameter = y[n_];
    pt.state = y.head(n_);
    const Eigen::MatrixXd jac = jacobian(y);
    pt.eigenvalues = sorted_eigenvalues(jac.leftCols(n_));
    pt.unstable = unstable_count(pt.eigenvalues);
    pt.residual = f(y).lpNorm<Eigen::Infinity>();
    pt.tangent = tangent(jac, previous);
    pt.iterations = iterations;
    return pt;
  }

  Eigen::VectorXd y_of(const EquilibriumPoint& pt) const {
    Eigen::VectorXd y(n_ + 1);
    y << pt.state, pt.parameter;
    return y;
  }

  // The start's point and the scales, in `direction` of the parameter.
  EquilibriumPoint start(const Equilibrium& start, int direction) {
    const double p0 = system_.parameter(start.parameters, parameter_);
    // The states' scale: what they are, or how far they move across the window if more (at
    // |dx/dp| from the start's tangent), so that a branch starting at x = 0 does not creep out of
    // it in steps of the floor.
    widen_scale(start.state);
    Eigen::VectorXd y0(n_ + 1);
    y0 << start.state, p0;
    Eigen::VectorXd along_p = Eigen::VectorXd::Zero(n_ + 1);
    along_p[n_] = 1.0;
    const Eigen::VectorXd t = tangent(jacobian(y0), along_p);
    if (std::abs(t[n_]) > 0) widen_scale(t.head(n_) / std::abs(t[n_]) * (o_.upper - o_.lower));
    Eigen::VectorXd along = Eigen::VectorXd::Zero(n_ + 1);
    along[n_] = direction / weights_[n_];
    return make_point(y0, along, 0);
  }

  const Eigen::VectorXd& weights() const { return weights_; }

  // F = f(x, p) and F_y = [f_x f_p], exact: Moore's system and the branching equation on them.
  MooreLinearize linearization() const {
    return [this](const Eigen::VectorXd& y) {
      MooreLinearization l;
      l.residual = f(y);
      l.jacobian = jacobian(y);
      l.ok = l.residual.allFinite() && l.jacobian.allFinite();
      if (!l.ok) l.failure = "the right-hand side or its Jacobian is not finite";
      return l;
    };
  }

  // Moore's regular system (branch_point.hpp) from `guess`, its noise that of exact derivatives:
  // F and F_y to a few rounding errors of their size.
  MooreSolution branch_point_near(const Eigen::VectorXd& guess) const {
    const Eigen::MatrixXd j = jacobian(guess);
    constexpr double kRounding = 64 * std::numeric_limits<double>::epsilon();
    const double residual_noise =
        kRounding * std::max(1.0, guess.head(n_).lpNorm<Eigen::Infinity>());
    const double jacobian_noise = kRounding * std::max(1.0, j.lpNorm<Eigen::Infinity>());
    BranchPointOptions o;
    o.max_iterations = 12;
    o.step_tolerance = 1e-13;
    return solve_moore(linearization(), weights_, guess, residual_noise, jacobian_noise, o);
  }

  // The driver's problem (driver.hpp).
  driver::Attempt<Point> step(const Point*, const Point& a, double ds) const {
    const Eigen::VectorXd ya = y_of(a);
    driver::Attempt<Point> r;
    r.point = correct(ya, a.tangent, ds, ya + ds * a.tangent, r.why);
    if (r.point) r.point->step = ds;
    return r;
  }
  double turn_cosine(const Point& a, const Point& b) const { return dot(b.tangent, a.tangent); }
  bool outside(const Point& b) const { return b.parameter <= o_.lower || b.parameter >= o_.upper; }
  std::string edge_message(const Point&) const { return "reached the parameter bound"; }
  double parameter(const Point& p) const { return p.parameter; }
  // The last point lies on the bound: f = 0 with the parameter fixed there.
  std::optional<Point> onto_edge(const Point& a, const Point& b) const {
    const double bound = std::clamp(b.parameter, o_.lower, o_.upper);
    const Equilibrium at = held_at(a, b, bound);
    if (!at.converged) return std::nullopt;
    Eigen::VectorXd y(n_ + 1);
    y << at.state, bound;
    Point p = make_point(y, a.tangent, at.iterations);
    const Eigen::VectorXd ya = y_of(a);
    p.step = std::sqrt(dot(y - ya, y - ya));
    return p;
  }
  driver::Found<Event> detect(const Point*, const Point& a, const Point& b) const {
    driver::Found<Event> found;
    if (o_.detect_bifurcations) found.events = events_between(a, b, b.step);
    for (const auto& e : found.events) found.unlocated |= !e.located;
    for (const double value : o_.user_points) {
      // Passed in this step (b on it counts; a on it was the step before's).
      if (!((a.parameter - value) * (b.parameter - value) < 0.0 || b.parameter == value)) continue;
      found.events.push_back(user_point(a, b, value));
    }
    std::stable_sort(found.events.begin(), found.events.end(),
                     [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
    return found;
  }
  std::optional<driver::Ending> ends(const Point&, const Point&, std::vector<Event>&) const {
    return std::nullopt;
  }
  void accept(Point& b) {
    widen_scale(b.state);
    b.tangent = unit(b.tangent);
  }

 private:
  // Events between a and b (b at arclength ds from a along a's tangent).
  std::vector<EquilibriumEvent> events_between(const EquilibriumPoint& a, const EquilibriumPoint& b,
                                               double ds) const {
    std::vector<EquilibriumEvent> events;
    using Tag = Complex;  // the eigenvalue followed (HB); unused by the other tests
    using Ends = driver::End<Tag>;
    const auto plain = [](auto g) {
      return [g](const EquilibriumPoint& pt, double, const Ends&, const Ends&) {
        return driver::Sample<Tag>{g(pt), Tag{}};
      };
    };
    const auto fold = [&](const EquilibriumPoint& pt) { return pt.tangent[n_]; };
    // A branch vertical in the parameter (chu's line of equilibria at alpha = 0) has a tangent
    // whose parameter component is rounding (1e-29 .. 1e-132 there), its sign noise: no fold.
    constexpr double kVertical = 1e-12;
    if (fold(a) * fold(b) < 0 && std::max(std::abs(fold(a)), std::abs(fold(b))) > kVertical)
      events.push_back(
          locate(a, b, ds, EquilibriumEventType::Fold, {fold(a), {}}, {fold(b), {}}, plain(fold)));
    // The bordered determinant with a's tangent as the border row throughout: its sign follows
    // the generalized cross product of [f_x f_p]'s rows, which vanishes and changes sign at a
    // branch point only (a point's own tangent there is ill-defined: the bordered system that
    // gives it is singular).
    const auto determinant = [&](const EquilibriumPoint& pt) {
      return bordered(jacobian(y_of(pt)), a.tangent).fullPivLu().determinant();
    };
    const double det_a = determinant(a), det_b = determinant(b);
    if (det_a * det_b < 0) {
      EquilibriumEvent e = locate(a, b, ds, EquilibriumEventType::BranchPoint, {det_a, {}},
                                  {det_b, {}}, plain(determinant));
      refine_branch_point(e, a, b);
      events.push_back(std::move(e));
    }
    // Complex pairs (upper halves) paired from a to b by least total distance.
    const int n = n_;
    Eigen::MatrixXd cost(n, n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) cost(i, j) = std::norm(a.eigenvalues[i] - b.eigenvalues[j]);
    const std::vector<int> to_b = least_cost_assignment(cost);
    const double size = std::max(1.0, a.eigenvalues.cwiseAbs().maxCoeff());
    for (int i = 0; i < n; ++i) {
      const Complex la = a.eigenvalues[i], lb = b.eigenvalues[to_b[i]];
      if (la.imag() <= 1e-9 * size || lb.imag() <= 1e-9 * size) continue;
      if ((la.real() > 0) == (lb.real() > 0)) continue;
      // The pair followed by continuity: the eigenvalue nearest to the value interpolated
      // between those followed at the bracket's ends.
      const auto followed = [](const EquilibriumPoint& pt, double s, const Ends& lo,
                               const Ends& hi) {
        const Complex expected =
            lo.sample.tag + (s - lo.s) / (hi.s - lo.s) * (hi.sample.tag - lo.sample.tag);
        const Complex mu = nearest_eigenvalue(pt.eigenvalues, expected);
        return driver::Sample<Tag>{mu.real(), mu};
      };
      Complex crossing;
      EquilibriumEvent e = locate(a, b, ds, EquilibriumEventType::Hopf, {la.real(), la},
                                  {lb.real(), lb}, followed, &crossing);
      e.hopf = describe_hopf(system_, values_at(e.parameter), e.state, crossing.imag());
      e.hopf->parameter = e.parameter;
      e.hopf->uncertainty = e.uncertainty;
      events.push_back(std::move(e));
    }
    // The number of eigenvalues in the right half plane, which only crossings change: one a fold
    // or branch point, two a Hopf pair. A change they do not explain (a pair that turned real
    // beside the axis, two crossings in one step) is reported unresolved, not located, so that
    // the driver tries the step shorter first.
    // On a branch where f_x stays singular (a line of equilibria at a fixed parameter value, as
    // chu's alpha = 0 through its branch point) an eigenvalue sits at zero all along and a branch
    // point there changes no count: parity says nothing where either end has one.
    int explained = 0;
    for (const auto& e : events) explained += e.type == EquilibriumEventType::Hopf ? 2 : 1;
    const int change = std::abs(b.unstable - a.unstable);
    const auto on_axis = [&](const EquilibriumPoint& pt) {
      for (const auto& l : pt.eigenvalues)
        if (std::abs(l.real()) <= 1e-9 * size && std::abs(l.imag()) <= 1e-9 * size) return true;
      return false;
    };
    const bool parity = !on_axis(a) && !on_axis(b);
    if (change > explained || (parity && (explained - change) % 2 != 0)) {
      EquilibriumEvent e;
      // Named by b's eigenvalue nearest the imaginary axis: a pair (HB) or real (BP).
      Complex nearest = b.eigenvalues[0];
      for (const auto& l : b.eigenvalues)
        if (std::abs(l.real()) < std::abs(nearest.real())) nearest = l;
      e.type = std::abs(nearest.imag()) > 1e-9 * size ? EquilibriumEventType::Hopf
                                                      : EquilibriumEventType::BranchPoint;
      e.after_point = a.index;
      e.parameter = 0.5 * (a.parameter + b.parameter);
      e.uncertainty = 0.5 * std::abs(b.parameter - a.parameter);
      e.state = 0.5 * (a.state + b.state);
      e.eigenvalues = b.eigenvalues;
      e.tangent = b.tangent;
      e.arclength = 0.5 * ds;
      e.note = "unresolved: the eigenvalues in the right half plane went from " +
               std::to_string(a.unstable) + " to " + std::to_string(b.unstable) +
               " between these points, which the crossings found do not explain";
      events.push_back(std::move(e));
    }
    std::sort(events.begin(), events.end(),
              [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
    return events;
  }

  // Newton with the parameter held at `value` (between a's and b's), from the state interpolated
  // linearly between them: a point on the window's edge, a user point.
  Equilibrium held_at(const EquilibriumPoint& a, const EquilibriumPoint& b, double value) const {
    const double w = (value - a.parameter) / (b.parameter - a.parameter);
    Equilibrium at = solve_equilibrium(system_, values_at(value), (1 - w) * a.state + w * b.state);
    if (!at.converged) at.state = (1 - w) * a.state + w * b.state;  // the guess, for a report
    return at;
  }

  EquilibriumEvent user_point(const EquilibriumPoint& a, const EquilibriumPoint& b,
                              double value) const {
    const double w = (value - a.parameter) / (b.parameter - a.parameter);
    EquilibriumEvent e;
    e.type = EquilibriumEventType::UserPoint;
    e.parameter = value;
    e.after_point = a.index;
    e.arclength = w * b.step;
    e.tangent = b.tangent;
    e.note = "user point";
    const Equilibrium at = held_at(a, b, value);
    e.located = at.converged;
    e.state = at.state;
    Eigen::VectorXd y(n_ + 1);
    y << e.state, value;
    e.eigenvalues = sorted_eigenvalues(jacobian(y).leftCols(n_));
    e.residual = f(y).lpNorm<Eigen::Infinity>();
    if (!at.converged)
      e.note += "; not located: Newton at this value failed (" + at.reason +
                "), the state interpolated between the points around it";
    return e;
  }

  // A BP located by the bordered determinant's sign change moved onto Moore's regular system:
  // near a branch point the corrector's points are resolved only to the residual over a vanishing
  // singular value, which left pp2's transcritical BP at 0.600014 (exact 0.6) unlocated. Its
  // uncertainty is then the system's (branch_point.hpp); where it fails, the crossing stands.
  void refine_branch_point(EquilibriumEvent& e, const EquilibriumPoint& a,
                           const EquilibriumPoint& b) const {
    const MooreSolution s = branch_point_near(y_of_event(e));
    const double lo = std::min(a.parameter, b.parameter), hi = std::max(a.parameter, b.parameter);
    if (!s.converged || s.y[n_] < lo - s.uncertainty || s.y[n_] > hi + s.uncertainty) {
      const std::string why =
          s.converged ? "its solution left the step that found the crossing" : s.reason;
      e.note += (e.note.empty() ? "" : "; ") +
                std::string("located by the crossing alone (the regular branch-point system: ") +
                why + ")";
      return;
    }
    e.parameter = s.y[n_];
    e.state = s.y.head(n_);
    e.uncertainty = s.uncertainty;
    e.located = true;
    e.eigenvalues = sorted_eigenvalues(s.jacobian.leftCols(n_));
    e.residual = s.residual;
    // The old branch's direction from the step's ends: at the branch point its own tangent is
    // any mix of the two branches' directions.
    e.tangent = unit(a.tangent + b.tangent);
    e.note = "located on the regular BP system";
  }
  Eigen::VectorXd y_of_event(const EquilibriumEvent& e) const {
    Eigen::VectorXd y(n_ + 1);
    y << e.state, e.parameter;
    return y;
  }

  // The one locator (crossing_locator.hpp) in the arclength from a along a's tangent, in [0, ds].
  template <class Test>
  EquilibriumEvent locate(const EquilibriumPoint& a, const EquilibriumPoint& b, double ds,
                          EquilibriumEventType type, driver::Sample<Complex> at_a,
                          driver::Sample<Complex> at_b, const Test& test,
                          Complex* crossing = nullptr) const {
    EquilibriumEvent e;
    e.type = type;
    e.after_point = a.index;
    const Eigen::VectorXd ya = y_of(a);
    const auto probe = [&](double s, std::string& why) {
      return correct(ya, a.tangent, s, ya + s * a.tangent, why);
    };
    driver::LocatorOptions lo;
    lo.tolerance = o_.location_tolerance;
    lo.floor = 0.01 * (o_.upper - o_.lower);
    lo.fold = type == EquilibriumEventType::Fold;
    lo.max_probes = 60;
    lo.probe_beside = true;
    auto c = driver::locate_crossing(
        a, at_a, b, at_b, ds, test, probe, [](const EquilibriumPoint& p) { return p.parameter; },
        lo);
    e.located = c.located();
    e.uncertainty = c.bracket;
    if (c.outcome == driver::LocatorOutcome::ProbeFailed)
      e.note = "a probe of the bracket could not be corrected: " + c.why;
    else if (!e.located)
      e.note = "not narrowed to the location tolerance";
    if (crossing) *crossing = c.sample.tag;
    e.parameter = c.point.parameter;
    e.state = std::move(c.point.state);
    e.eigenvalues = std::move(c.point.eigenvalues);
    e.residual = c.point.residual;
    e.tangent = std::move(c.point.tangent);
    e.arclength = c.s;
    return e;
  }

  const OdeSystem& system_;
  int parameter_;
  ParameterValues base_;
  const EquilibriumOptions& o_;
  int n_;
  double scale_ = 0.0;
  Eigen::VectorXd weights_;
};

inline driver::Options equilibrium_driver_options(const EquilibriumOptions& o) {
  driver::Options d = driver::step_options(o);
  d.location_retries = 3;  // an event not located (or a count not explained): a shorter step
  // Newton with exact derivatives: a step that took at most 3 iterations is doubled.
  d.rule = {3, 2.0, 2.0, std::numeric_limits<int>::max(), 1.0};
  return d;
}

}  // namespace sympathy::detail
