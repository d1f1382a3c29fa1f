#include "sympathy/continuation/equilibrium_branch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sympathy/core/assignment.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

OptionCheck EquilibriumOptions::validate() const {
  if (!positive(initial_step)) return OptionProblem{"initial_step", "a positive number"};
  if (!positive(min_step) || min_step > initial_step)
    return OptionProblem{"min_step", "a positive number no larger than initial_step"};
  if (!positive(max_step) || max_step < initial_step)
    return OptionProblem{"max_step", "a number no smaller than initial_step"};
  if (max_points < 2) return OptionProblem{"max_points", "an integer of at least 2"};
  if (max_iterations < 2 || max_iterations > 50)
    return OptionProblem{"max_iterations", "an integer from 2 to 50"};
  if (!positive(tolerance) || tolerance >= 1e-3)
    return OptionProblem{"tolerance", "a positive number below 1e-3"};
  if (!positive(state_scale_floor)) return OptionProblem{"state_scale_floor", "a positive number"};
  if (!(min_tangent_cosine > 0.0 && min_tangent_cosine < 1.0))
    return OptionProblem{"min_tangent_cosine", "a number between 0 and 1"};
  if (!positive(location_tolerance) || location_tolerance >= 0.1)
    return OptionProblem{"location_tolerance", "a positive number below 0.1"};
  return std::nullopt;
}

std::string to_string(EquilibriumEventType t) {
  switch (t) {
    case EquilibriumEventType::Fold:
      return "LP";
    case EquilibriumEventType::BranchPoint:
      return "BP";
    case EquilibriumEventType::Hopf:
      return "HB";
  }
  return "?";
}

std::string to_string(EquilibriumStop s) {
  switch (s) {
    case EquilibriumStop::ParameterBound:
      return "parameter bound";
    case EquilibriumStop::PointLimit:
      return "point limit";
    case EquilibriumStop::MinimumStep:
      return "minimum step";
    case EquilibriumStop::Interrupted:
      return "interrupted";
    case EquilibriumStop::StartFailed:
      return "start failed";
  }
  return "?";
}

std::string EquilibriumProblem::problem_with(const OdeSystem& system) const {
  if (parameter < 0 || parameter >= system.parameter_count())
    return "parameter: expected the index of a named parameter";
  if (values.size() != system.parameter_values_size())
    return "values: expected " + std::to_string(system.parameter_values_size()) + " values";
  if (!std::isfinite(from) || !std::isfinite(to) || from == to)
    return "from, to: expected two different finite values";
  if (at && !(*at > std::min(from, to) && *at < std::max(from, to)))
    return "at " + format_double(*at) + ": expected a value strictly between from and to";
  if (start_state.size() != system.dimension())
    return "start_state: expected " + std::to_string(system.dimension()) + " values";
  if (auto wrong = newton.validate()) return "newton." + wrong->message();
  return "";
}

namespace {

using Complex = std::complex<double>;

// One way along a branch of equilibria (the pieces of the header's comment).
class Run {
 public:
  Run(const OdeSystem& system, int parameter, ParameterValues base, const EquilibriumOptions& o)
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

  // Newton on f = 0 and <t, y - from> = s, from `guess`; nullopt if it fails.
  std::optional<EquilibriumPoint> correct(const Eigen::VectorXd& from, const Eigen::VectorXd& t,
                                          double s, Eigen::VectorXd y) const {
    const Eigen::VectorXd row = weights_.cwiseProduct(weights_).cwiseProduct(t);
    for (int it = 1; it <= o_.max_iterations; ++it) {
      Eigen::VectorXd g(n_ + 1);
      g.head(n_) = f(y);
      g[n_] = row.dot(y - from) - s;
      if (!g.allFinite()) return std::nullopt;
      Eigen::MatrixXd m(n_ + 1, n_ + 1);
      m.topRows(n_) = jacobian(y);
      m.row(n_) = row.transpose();
      Eigen::FullPivLU<Eigen::MatrixXd> lu(m);
      if (!lu.isInvertible()) return std::nullopt;
      const Eigen::VectorXd dy = lu.solve(-g);
      y += dy;
      if (!y.allFinite()) return std::nullopt;
      const double x_size = std::max(1.0, y.head(n_).lpNorm<Eigen::Infinity>());
      const double p_size = std::max(1.0, std::abs(y[n_]));
      if (dy.head(n_).lpNorm<Eigen::Infinity>() <= o_.tolerance * x_size &&
          std::abs(dy[n_]) <= o_.tolerance * p_size)
        return make_point(y, t, it);
    }
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

  // Events between a and b (b at arclength ds from a along a's tangent).
  std::vector<EquilibriumEvent> detect(const EquilibriumPoint& a, const EquilibriumPoint& b,
                                       double ds) const {
    std::vector<EquilibriumEvent> events;
    if (a.tangent[n_] * b.tangent[n_] < 0)
      events.push_back(locate(a, ds, EquilibriumEventType::Fold,
                              [&](const EquilibriumPoint& pt) { return pt.tangent[n_]; }));
    // The bordered determinant with a's tangent as the border row throughout: its sign follows
    // the generalized cross product of [f_x f_p]'s rows, which vanishes and changes sign at a
    // branch point only (a point's own tangent there is ill-defined: the bordered system that
    // gives it is singular).
    const auto determinant = [&](const EquilibriumPoint& pt) {
      return bordered(jacobian(y_of(pt)), a.tangent).fullPivLu().determinant();
    };
    if (determinant(a) * determinant(b) < 0)
      events.push_back(locate(a, ds, EquilibriumEventType::BranchPoint, determinant));
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
      Complex followed = la;
      EquilibriumEvent e =
          locate(a, ds, EquilibriumEventType::Hopf, [&](const EquilibriumPoint& pt) {
            followed = nearest_eigenvalue(pt.eigenvalues, followed);
            return followed.real();
          });
      e.hopf = describe_hopf(system_, values_at(e.parameter), e.state, followed.imag());
      e.hopf->parameter = e.parameter;
      e.hopf->uncertainty = e.uncertainty;
      events.push_back(std::move(e));
    }
    std::sort(events.begin(), events.end(),
              [](const auto& x, const auto& y) { return x.arclength < y.arclength; });
    return events;
  }

  // Illinois regula falsi on g(s), s the arclength from a along a's tangent, in [0, ds].
  template <class G>
  EquilibriumEvent locate(const EquilibriumPoint& a, double ds, EquilibriumEventType type,
                          G g) const {
    EquilibriumEvent e;
    e.type = type;
    e.after_point = a.index;
    const Eigen::VectorXd ya = y_of(a);
    auto probe = [&](double s) { return correct(ya, a.tangent, s, ya + s * a.tangent); };
    double s_lo = 0.0, s_hi = ds;
    std::optional<EquilibriumPoint> lo = a, hi = probe(ds);
    if (!hi) {
      e.note = "the bracket's end could not be corrected";
      return e;
    }
    double g_lo = g(*lo), g_hi = g(*hi);
    const bool lo_best = std::abs(g_lo) < std::abs(g_hi);
    std::optional<EquilibriumPoint> best = lo_best ? lo : hi;
    double best_s = lo_best ? s_lo : s_hi, best_g = std::abs(lo_best ? g_lo : g_hi);
    const double floor = 0.01 * (o_.upper - o_.lower);
    int last = 0;  // which end the last probe replaced (+1 lo, -1 hi): Illinois halves the other
    for (int k = 0; k < 60; ++k) {
      const double width = std::abs(hi->parameter - lo->parameter);
      if (width <= o_.location_tolerance * std::max(std::abs(best->parameter), floor) ||
          best_g == 0.0) {
        e.located = true;
        e.uncertainty = width;
        break;
      }
      double s =
          (g_hi - g_lo) != 0 ? s_lo - g_lo * (s_hi - s_lo) / (g_hi - g_lo) : 0.5 * (s_lo + s_hi);
      if (!(s > s_lo && s < s_hi)) s = 0.5 * (s_lo + s_hi);
      auto mid = probe(s);
      // Regula falsi can land on the event itself (exactly, where g is linear), where the
      // bordered system of a branch point is singular: a probe beside it serves as well.
      for (const double nudge : {1e-3, -1e-3})
        if (!mid) {
          const double moved = s + nudge * (s_hi - s_lo);
          mid = probe(moved);
          if (mid) s = moved;
        }
      if (!mid) {
        e.note = "a probe of the bracket could not be corrected";
        break;
      }
      const double g_mid = g(*mid);
      if (std::abs(g_mid) <= best_g) {
        best = mid;
        best_s = s;
        best_g = std::abs(g_mid);
      }
      if ((g_mid > 0) == (g_lo > 0)) {
        s_lo = s;
        lo = std::move(mid);
        g_lo = g_mid;
        if (last == 1) g_hi *= 0.5;
        last = 1;
      } else {
        s_hi = s;
        hi = std::move(mid);
        g_hi = g_mid;
        if (last == -1) g_lo *= 0.5;
        last = -1;
      }
    }
    if (!e.located) e.uncertainty = std::abs(hi->parameter - lo->parameter);
    e.parameter = best->parameter;
    e.state = best->state;
    e.eigenvalues = best->eigenvalues;
    e.residual = best->residual;
    e.tangent = best->tangent;
    e.arclength = best_s;
    return e;
  }

  EquilibriumBranch run(const Equilibrium& start, int direction,
                        const EquilibriumCallbacks& callbacks) {
    EquilibriumBranch branch;
    const double p0 = system_.parameter(start.parameters, parameter_);
    // The states' scale: what they are, or how far they move across the window if more (at
    // |dx/dp| from the start's tangent), so that a branch starting at x = 0 does not creep out of
    // it in steps of the floor.
    widen_scale(start.state);
    {
      Eigen::VectorXd y(n_ + 1);
      y << start.state, p0;
      Eigen::VectorXd along_p = Eigen::VectorXd::Zero(n_ + 1);
      along_p[n_] = 1.0;
      const Eigen::VectorXd t = tangent(jacobian(y), along_p);
      if (std::abs(t[n_]) > 0) widen_scale(t.head(n_) / std::abs(t[n_]) * (o_.upper - o_.lower));
    }
    Eigen::VectorXd along = Eigen::VectorXd::Zero(n_ + 1);
    along[n_] = direction / weights_[n_];
    Eigen::VectorXd y0(n_ + 1);
    y0 << start.state, p0;
    branch.points.push_back(make_point(y0, along, 0));
    if (callbacks.on_point) callbacks.on_point(branch.points.back());
    double ds = o_.initial_step;
    for (;;) {
      if (callbacks.stop_requested && callbacks.stop_requested()) {
        branch.stop = EquilibriumStop::Interrupted;
        branch.stop_reason = "interrupted";
        return branch;
      }
      if (static_cast<int>(branch.points.size()) >= o_.max_points) {
        branch.stop = EquilibriumStop::PointLimit;
        branch.stop_reason = "point limit (" + std::to_string(o_.max_points) + ") reached";
        return branch;
      }
      const EquilibriumPoint& a = branch.points.back();
      const Eigen::VectorXd ya = y_of(a);
      auto b = correct(ya, a.tangent, ds, ya + ds * a.tangent);
      if (b && dot(b->tangent, a.tangent) < o_.min_tangent_cosine && ds > 4 * o_.min_step)
        b.reset();
      if (!b) {
        ds *= 0.5;
        if (ds < o_.min_step) {
          branch.stop = EquilibriumStop::MinimumStep;
          branch.stop_reason = "step size below the minimum: the corrector kept failing";
          return branch;
        }
        continue;
      }
      b->index = a.index + 1;
      b->step = ds;
      // The last point lies on the bound: f = 0 with the parameter fixed there.
      bool on_bound = false;
      const double bound = std::clamp(b->parameter, o_.lower, o_.upper);
      if (bound != b->parameter) {
        const double w = (bound - a.parameter) / (b->parameter - a.parameter);
        const Equilibrium at =
            solve_equilibrium(system_, values_at(bound), (1 - w) * a.state + w * b->state);
        if (at.converged) {
          Eigen::VectorXd y(n_ + 1);
          y << at.state, bound;
          const int index = b->index;
          b = make_point(y, a.tangent, at.iterations);
          b->index = index;
          b->step = std::sqrt(dot(y - ya, y - ya));
          on_bound = true;
        }
      }
      std::vector<EquilibriumEvent> events;
      if (o_.detect_bifurcations) events = detect(a, *b, b->step);
      branch.points.push_back(std::move(*b));
      const EquilibriumPoint& added = branch.points.back();
      if (callbacks.on_point) callbacks.on_point(added);
      for (auto& e : events) {
        branch.events.push_back(std::move(e));
        if (callbacks.on_event) callbacks.on_event(branch.events.back());
      }
      if (on_bound || added.parameter <= o_.lower || added.parameter >= o_.upper) {
        branch.stop = EquilibriumStop::ParameterBound;
        branch.stop_reason = "reached the parameter bound";
        return branch;
      }
      widen_scale(added.state);
      branch.points.back().tangent = unit(added.tangent);
      ds = added.iterations <= 3 ? std::min(2.0 * ds, o_.max_step) : ds;
    }
  }

 private:
  const OdeSystem& system_;
  int parameter_;
  ParameterValues base_;
  const EquilibriumOptions& o_;
  int n_;
  double scale_ = 0.0;
  Eigen::VectorXd weights_;
};

}  // namespace

EquilibriumBranch continue_equilibria(const OdeSystem& system, const EquilibriumProblem& problem,
                                      EquilibriumOptions options,
                                      const EquilibriumCallbacks& callbacks) {
  const Stopwatch started;
  if (const std::string wrong = problem.problem_with(system); !wrong.empty())
    throw std::invalid_argument("equilibria: " + wrong);
  options.lower = std::min(problem.from, problem.to);
  options.upper = std::max(problem.from, problem.to);
  if (auto wrong = options.validate())
    throw std::invalid_argument("equilibria: " + wrong->message());
  EquilibriumBranch branch;
  branch.parameter = problem.parameter;
  branch.parameter_name = system.parameter_names()[problem.parameter];
  branch.state_names = system.state_names();
  branch.options = options;
  const double first = problem.first_value();
  branch.start_values = system.with_parameter(problem.values, problem.parameter, first);
  const Equilibrium start =
      solve_equilibrium(system, branch.start_values, problem.start_state, problem.newton);
  if (!start.converged) {
    branch.stop = EquilibriumStop::StartFailed;
    branch.stop_reason = "no equilibrium near the start at " + branch.parameter_name + " = " +
                         format_double(first) + ": " + start.reason;
    branch.seconds = started.seconds();
    return branch;
  }
  auto one_way = [&](double to, const EquilibriumCallbacks& cb) {
    Run run(system, problem.parameter, branch.start_values, options);
    return run.run(start, to > first ? 1 : -1, cb);
  };
  if (!problem.at) {
    EquilibriumBranch forward = one_way(problem.to, callbacks);
    branch.points = std::move(forward.points);
    branch.events = std::move(forward.events);
    branch.stop = forward.stop;
    branch.stop_reason = forward.stop_reason;
  } else {
    // Backward first, reported as it comes with negative indices, then forward.
    EquilibriumCallbacks back = callbacks;
    if (callbacks.on_point)
      back.on_point = [&](const EquilibriumPoint& pt) {
        if (pt.index == 0) return;  // the start is reported once, by the forward run
        EquilibriumPoint q = pt;
        q.index = -pt.index;
        callbacks.on_point(q);
      };
    EquilibriumBranch backward = one_way(problem.from, back);
    EquilibriumBranch forward = one_way(problem.to, callbacks);
    for (auto it = backward.points.rbegin(); it != backward.points.rend(); ++it) {
      if (it->index == 0) continue;
      EquilibriumPoint q = *it;
      q.index = -q.index;
      q.tangent = -q.tangent;
      branch.points.push_back(std::move(q));
    }
    for (auto& pt : forward.points) branch.points.push_back(std::move(pt));
    for (auto it = backward.events.rbegin(); it != backward.events.rend(); ++it) {
      EquilibriumEvent e = *it;
      e.after_point = -e.after_point - 1;
      branch.events.push_back(std::move(e));
    }
    for (auto& e : forward.events) branch.events.push_back(std::move(e));
    branch.stop = forward.stop;
    branch.stop_reason = "backward: " + backward.stop_reason + "; forward: " + forward.stop_reason;
    if (backward.stop == EquilibriumStop::Interrupted) branch.stop = backward.stop;
  }
  branch.seconds = started.seconds();
  return branch;
}

}  // namespace sympathy
