#include "sympathy/continuation/equilibrium_curve.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/SVD>

#include "bordered_newton.hpp"
#include "codim2_coefficients.hpp"
#include "nearest_eigen.hpp"
#include "sympathy/continuation/crossing_locator.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

OptionCheck EquilibriumCurveOptions::validate() const {
  if (!(first_lower < first_upper)) return OptionProblem{"first window", "lower below upper"};
  if (!(second_lower < second_upper)) return OptionProblem{"second window", "lower below upper"};
  // The steps, their point limit and the turn: the driver's own checks.
  if (auto wrong = driver::step_options(*this).validate()) return wrong;
  if (max_iterations < 2 || max_iterations > 50)
    return OptionProblem{"max_iterations", "an integer from 2 to 50"};
  if (!positive(tolerance) || tolerance >= 1e-3)
    return OptionProblem{"tolerance", "a positive number below 1e-3"};
  if (!positive(location_tolerance) || location_tolerance >= 0.1)
    return OptionProblem{"location_tolerance", "a positive number below 0.1"};
  for (const Value& v : user_values)
    if (!std::isfinite(v.value)) return OptionProblem{"user_values", "finite values"};
  return std::nullopt;
}

namespace {

using Complex = std::complex<double>;
using Point = EquilibriumCurvePoint;
using Event = EquilibriumCurveEvent;

// Central differences of the augmented rows, in the scaled norm: f_x is exact, so a bordered
// solve is good to rounding and its difference to about 1e-12 relative at this step.
constexpr double kDifference = 1e-6;

// The curve as the driver's problem.
class CurveProblem {
 public:
  using Point = EquilibriumCurvePoint;
  using Event = EquilibriumCurveEvent;

  CurveProblem(const OdeSystem& system, bool hopf, int first, int second, ParameterValues base,
               const EquilibriumCurveOptions& o)
      : system_(system),
        hopf_(hopf),
        first_(first),
        second_(second),
        base_(std::move(base)),
        o_(o),
        n_(system.dimension()),
        size_(n_ + (hopf ? 3 : 2)),
        equations_(n_ + (hopf ? 2 : 1)),
        weights_(Eigen::VectorXd::Ones(size_)) {
    weights_[n_] = 1.0 / (o_.first_upper - o_.first_lower);
    weights_[n_ + 1] = 1.0 / (o_.second_upper - o_.second_lower);
  }

  int size() const { return size_; }
  const Eigen::VectorXd& weights() const { return weights_; }
  void widen_scale(const Eigen::VectorXd& x, double kappa) {
    widen_scale(x.lpNorm<Eigen::Infinity>(), kappa);
  }
  void widen_scale(double x, double kappa) {
    scale_ = std::max({scale_, 1e-3, x});
    weights_.head(n_).setConstant(1.0 / scale_);
    if (hopf_) {
      kappa_scale_ = std::max({kappa_scale_, 1e-3, std::abs(kappa)});
      weights_[n_ + 2] = 1.0 / kappa_scale_;
    }
  }
  double dot(const Eigen::VectorXd& u, const Eigen::VectorXd& v) const {
    return weights_.cwiseProduct(u).dot(weights_.cwiseProduct(v));
  }
  Eigen::VectorXd unit(const Eigen::VectorXd& u) const { return u / std::sqrt(dot(u, u)); }

  ParameterValues values_at(const Eigen::VectorXd& y) const {
    return system_.with_parameter(system_.with_parameter(base_, first_, y[n_]), second_, y[n_ + 1]);
  }
  Eigen::MatrixXd a_of(const Eigen::VectorXd& y) const {
    Eigen::MatrixXd a;
    const ParameterValues p = values_at(y);
    system_.jacobian(0.0, y.data(), p.data(), a);
    return a;
  }
  // The matrix whose kernel the curve keeps: A (LP) or A^2 + kappa I (HB).
  Eigen::MatrixXd singular_of(const Eigen::VectorXd& y) const {
    const Eigen::MatrixXd a = a_of(y);
    if (!hopf_) return a;
    return a * a + y[n_ + 2] * Eigen::MatrixXd::Identity(n_, n_);
  }
  int border_width() const { return hopf_ ? 2 : 1; }

  // The borders from the singular matrix's smallest singular vectors at y.
  void set_borders(Point& p, const Eigen::VectorXd& y) const {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(singular_of(y),
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    const int k = border_width();
    Eigen::MatrixXd right = svd.matrixV().rightCols(k), left = svd.matrixU().rightCols(k);
    // Oriented along the previous borders, where there are any, so that the test functions
    // built on them stay continuous.
    if (p.right.cols() == k) {
      right = right * procrustes(right, p.right);
      left = left * procrustes(left, p.left);
    }
    p.right = right;
    p.left = left;
  }
  // The rotation R of the columns of `x` best matching `target` (x R ~ target).
  static Eigen::MatrixXd procrustes(const Eigen::MatrixXd& x, const Eigen::MatrixXd& target) {
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(x.transpose() * target,
                                                Eigen::ComputeFullU | Eigen::ComputeFullV);
    return svd.matrixU() * svd.matrixV().transpose();
  }

  // The bordered solve: G (k x k) and the null vectors V (n x k) and W (n x k, transposed
  // system's) for the borders of `borders`.
  struct Bordered {
    Eigen::MatrixXd g, v, w;
  };
  Bordered bordered(const Eigen::MatrixXd& s, const Point& borders) const {
    const int k = border_width();
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(n_ + k, n_ + k);
    m.topLeftCorner(n_, n_) = s;
    m.topRightCorner(n_, k) = borders.left;
    m.bottomLeftCorner(k, n_) = borders.right.transpose();
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n_ + k, k);
    rhs.bottomRows(k).setIdentity();
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m);
    const Eigen::MatrixXd vg = lu.solve(rhs);
    const Eigen::MatrixXd wg = lu.transpose().solve(rhs);
    return {vg.bottomRows(k), vg.topRows(n_), wg.topRows(n_)};
  }
  // The augmented system's equations beyond f: g (LP) or G's two entries (HB).
  Eigen::VectorXd g_of(const Eigen::VectorXd& y, const Point& borders) const {
    const Bordered b = bordered(singular_of(y), borders);
    if (!hopf_) return Eigen::VectorXd::Constant(1, b.g(0, 0));
    const Eigen::Map<const Eigen::VectorXd> entries(b.g.data(), 4);
    return Eigen::Vector2d(entries[borders.entry_a], entries[borders.entry_b]);
  }
  // Every entry of G (column-major), for the choice of the two.
  Eigen::VectorXd all_entries(const Eigen::VectorXd& y, const Point& borders) const {
    const Bordered b = bordered(singular_of(y), borders);
    return Eigen::Map<const Eigen::VectorXd>(b.g.data(), b.g.size());
  }

  Eigen::VectorXd residual(const Eigen::VectorXd& y, const Point& borders) const {
    Eigen::VectorXd r(equations_);
    r.head(n_) = system_.rhs(0.0, Eigen::VectorXd(y.head(n_)), values_at(y));
    r.tail(equations_ - n_) = g_of(y, borders);
    return r;
  }
  // d(entries)/dy by central differences, each row one entry.
  template <class Entries>
  Eigen::MatrixXd differences(const Eigen::VectorXd& y, const Entries& entries, int rows) const {
    Eigen::MatrixXd d(rows, size_);
    for (int j = 0; j < size_; ++j) {
      const double h = kDifference / weights_[j];
      Eigen::VectorXd up = y, down = y;
      up[j] += h;
      down[j] -= h;
      d.col(j) = (entries(up) - entries(down)) / (2 * h);
    }
    return d;
  }
  Eigen::MatrixXd jacobian(const Eigen::VectorXd& y, const Point& borders) const {
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(equations_, size_);
    const ParameterValues p = values_at(y);
    j.topLeftCorner(n_, n_) = a_of(y);
    Eigen::VectorXd fp(n_);
    system_.parameter_derivative(0.0, y.data(), p.data(), first_, fp.data());
    j.col(n_).head(n_) = fp;
    system_.parameter_derivative(0.0, y.data(), p.data(), second_, fp.data());
    j.col(n_ + 1).head(n_) = fp;
    j.bottomRows(equations_ - n_) = differences(
        y, [&](const Eigen::VectorXd& z) { return g_of(z, borders); }, equations_ - n_);
    return j;
  }
  // The unit tangent at y, oriented along `previous`.
  Eigen::VectorXd tangent(const Eigen::MatrixXd& j, const Eigen::VectorXd& previous) const {
    Eigen::MatrixXd m(size_, size_);
    m.topRows(equations_) = j;
    m.row(size_ - 1) = weights_.cwiseProduct(weights_).cwiseProduct(previous).transpose();
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(size_);
    rhs[size_ - 1] = 1.0;
    Eigen::VectorXd t = unit(m.fullPivLu().solve(rhs));
    if (dot(t, previous) < 0) t = -t;
    return t;
  }

  // Newton on the curve's equations and one more, row^T y = value, from `y`, with the borders
  // (and entries) of `borders`; the point made at convergence, nullopt with the reason if not.
  std::optional<Point> correct(Eigen::VectorXd y, const Eigen::VectorXd& row, double value,
                               const Point& borders, const Eigen::VectorXd& previous,
                               std::string& why) const {
    for (int it = 1; it <= o_.max_iterations; ++it) {
      const auto dy = detail::bordered_newton_step(jacobian(y, borders), row, residual(y, borders),
                                                   row.dot(y) - value, "augmented system", why);
      if (!dy) return std::nullopt;
      y += *dy;
      if (dy->cwiseAbs().maxCoeff() <= o_.tolerance * std::max(1.0, y.lpNorm<Eigen::Infinity>()))
        return make_point(y, borders, previous, it);
    }
    why = "Newton did not converge in " + std::to_string(o_.max_iterations) + " iterations";
    return std::nullopt;
  }

  Eigen::VectorXd y_of(const Point& p) const {
    Eigen::VectorXd y(size_);
    y.head(n_) = p.state;
    y[n_] = p.first;
    y[n_ + 1] = p.second;
    if (hopf_) y[n_ + 2] = p.kappa;
    return y;
  }

  Point make_point(const Eigen::VectorXd& y, const Point& borders, const Eigen::VectorXd& previous,
                   int iterations) const {
    Point p;
    p.first = y[n_];
    p.second = y[n_ + 1];
    p.state = y.head(n_);
    const Eigen::MatrixXd a = a_of(y);
    p.eigenvalues = sorted_eigenvalues(a);
    p.residual =
        system_.rhs(0.0, Eigen::VectorXd(y.head(n_)), values_at(y)).lpNorm<Eigen::Infinity>();
    p.iterations = iterations;
    p.right = borders.right;
    p.left = borders.left;
    p.entry_a = borders.entry_a;
    p.entry_b = borders.entry_b;
    if (hopf_) {
      p.kappa = y[n_ + 2];
      p.neutral_saddle = p.kappa < 0.0;
      if (p.kappa > 0.0) {
        const HopfPoint h = describe_hopf(system_, values_at(y), p.state, std::sqrt(p.kappa));
        if (h.lyapunov) p.lyapunov = *h.lyapunov;
      }
    }
    p.tangent = tangent(jacobian(y, borders), previous);
    return p;
  }

  // The borders renewed at p (and, on a Hopf curve, the two entries of G that keep the system's
  // Jacobian best conditioned: the largest least singular value over the six pairs).
  void renew(Point& p, const Eigen::VectorXd& y) const {
    set_borders(p, y);
    if (!hopf_) return;
    Eigen::MatrixXd j(n_ + 4, size_);
    j.topRows(n_) = jacobian_f(y);
    j.bottomRows(4) = differences(
        y, [&](const Eigen::VectorXd& z) { return all_entries(z, p); }, 4);
    double best = -1.0;
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        Eigen::MatrixXd m(n_ + 2, size_);
        m.topRows(n_) = j.topRows(n_);
        m.row(n_) = j.row(n_ + a);
        m.row(n_ + 1) = j.row(n_ + b);
        const double least =
            Eigen::JacobiSVD<Eigen::MatrixXd>(m * weights_.cwiseInverse().asDiagonal())
                .singularValues()
                .minCoeff();
        if (least > best) {
          best = least;
          p.entry_a = a;
          p.entry_b = b;
        }
      }
  }
  Eigen::MatrixXd jacobian_f(const Eigen::VectorXd& y) const {
    Eigen::MatrixXd j = Eigen::MatrixXd::Zero(n_, size_);
    const ParameterValues p = values_at(y);
    j.leftCols(n_) = a_of(y);
    Eigen::VectorXd fp(n_);
    system_.parameter_derivative(0.0, y.data(), p.data(), first_, fp.data());
    j.col(n_) = fp;
    system_.parameter_derivative(0.0, y.data(), p.data(), second_, fp.data());
    j.col(n_ + 1) = fp;
    return j;
  }

  // The driver's problem (driver.hpp).
  driver::Attempt<Point> step(const Point*, const Point& a, double ds) const {
    const Eigen::VectorXd ya = y_of(a);
    const Eigen::VectorXd row = weights_.cwiseProduct(weights_).cwiseProduct(a.tangent);
    driver::Attempt<Point> r;
    r.point = correct(ya + ds * a.tangent, row, row.dot(ya) + ds, a, a.tangent, r.why);
    if (r.point) r.point->step = ds;
    return r;
  }
  double turn_cosine(const Point& a, const Point& b) const { return dot(a.tangent, b.tangent); }
  bool outside(const Point& b) const {
    return b.first <= o_.first_lower || b.first >= o_.first_upper || b.second <= o_.second_lower ||
           b.second >= o_.second_upper;
  }
  std::string edge_message(const Point& b) const {
    return b.first <= o_.first_lower || b.first >= o_.first_upper
               ? "reached the first parameter's bound"
               : "reached the second parameter's bound";
  }
  double parameter(const Point& p) const { return p.second; }
  std::optional<Point> onto_edge(const Point& a, const Point& b) const {
    const bool in_first = b.first <= o_.first_lower || b.first >= o_.first_upper;
    const int k = in_first ? n_ : n_ + 1;
    const double bound = in_first ? std::clamp(b.first, o_.first_lower, o_.first_upper)
                                  : std::clamp(b.second, o_.second_lower, o_.second_upper);
    const Eigen::VectorXd ya = y_of(a), yb = y_of(b);
    const double w = (bound - ya[k]) / (yb[k] - ya[k]);
    std::string why;
    auto p =
        correct((1 - w) * ya + w * yb, Eigen::VectorXd::Unit(size_, k), bound, a, a.tangent, why);
    if (p) {
      const Eigen::VectorXd d = y_of(*p) - ya;
      p->step = std::sqrt(dot(d, d));
    }
    return p;
  }
  driver::Found<Event> detect(const Point*, const Point& a, const Point& b) const {
    driver::Found<Event> found;
    if (!o_.detect) {
      user_points(a, b, found);
      return found;
    }
    const Eigen::VectorXd ya = y_of(a);
    const auto probe = [&](double s, std::string& why) {
      const Eigen::VectorXd row = weights_.cwiseProduct(weights_).cwiseProduct(a.tangent);
      return correct(ya + s * a.tangent, row, row.dot(ya) + s, a, a.tangent, why);
    };
    for (const auto& [type, description] : tests()) {
      const auto test = [&, type = type](const Point& p, double, const driver::End<int>&,
                                         const driver::End<int>&) {
        return driver::Sample<int>{test_value(type, p, a), 0};
      };
      const double at_a = test_value(type, a, a), at_b = test_value(type, b, a);
      if (!(std::isfinite(at_a) && std::isfinite(at_b)) || !(at_a * at_b < 0)) continue;
      driver::LocatorOptions lo;
      lo.tolerance = o_.location_tolerance;
      lo.floor = 0.01 * (o_.second_upper - o_.second_lower);
      lo.max_probes = 60;
      lo.probe_beside = true;  // a singular probe (a branch point of the curve) tried beside
      // Where the curve runs more along the first parameter than the second (relative to their
      // windows), a bracket narrow in the second says little: the arclength must narrow too.
      // (On the line b2 = 0.25 of two Hopf pairs its HH was "located" 0.076 off in b1.)
      lo.fold = std::abs(b.second - a.second) * (o_.first_upper - o_.first_lower) <
                std::abs(b.first - a.first) * (o_.second_upper - o_.second_lower);
      const auto c = driver::locate_crossing(
          a, driver::Sample<int>{at_a, 0}, b, driver::Sample<int>{at_b, 0}, b.step, test, probe,
          [](const Point& p) { return p.second; }, lo);
      Event e;
      e.type = type;
      e.description = description;
      e.located = c.located();
      e.uncertainty = c.bracket;
      e.first = c.point.first;
      e.second = c.point.second;
      e.at = c.point;
      e.arclength = c.s;
      e.after_point = a.index;
      // The point the curve starts at, if it is one of these (a switch at a codimension-two
      // point): its test is zero there, and the first step sees it change sign. Its origin
      // names it.
      if (a.index == 0 && e.located && start_ &&
          std::hypot((e.first - start_->first) / (o_.first_upper - o_.first_lower),
                     (e.second - start_->second) / (o_.second_upper - o_.second_lower)) <= 1e-6)
        continue;
      if (e.located) add_coefficients(e);
      if (!e.located)
        e.note = c.outcome == driver::LocatorOutcome::ProbeFailed
                     ? "a probe of the bracket could not be corrected: " + c.why
                     : "not narrowed to the location tolerance";
      found.unlocated |= !e.located;
      found.events.push_back(std::move(e));
    }
    user_points(a, b, found);
    std::sort(found.events.begin(), found.events.end(),
              [](const Event& x, const Event& y) { return x.arclength < y.arclength; });
    return found;
  }
  // A value asked to stop at, passed in this step: the curve ends there, the events beyond it
  // dropped and b not kept (the point there is the event's).
  std::optional<driver::Ending> ends(const Point&, const Point&, std::vector<Event>& events) const {
    for (std::size_t i = 0; i < events.size(); ++i)
      if (events[i].type == "UZ" && events[i].note.rfind("stop at", 0) == 0) {
        const std::string note = events[i].note;
        events.resize(i + 1);
        return driver::Ending{driver::Stop::UserValue, "reached the value asked for: " + note,
                              false};
      }
    return std::nullopt;
  }
  void set_start(const Point& p) { start_ = std::pair{p.first, p.second}; }
  void accept(Point& b) {
    widen_scale(b.state, hopf_ ? b.kappa : 0.0);
    renew(b, y_of(b));
    b.tangent = unit(b.tangent);
  }

 private:
  void add_coefficients(Event& e) const {
    const Eigen::VectorXd y = y_of(e.at);
    const ParameterValues p = values_at(y);
    if (e.type == "BT") {
      if (const auto c = detail::bogdanov_takens_coefficients(system_, p, e.at.state)) {
        e.coefficients = {{"a", c->a}, {"b", c->b}};
        e.note = "a = " + format_double(c->a) + ", b = " + format_double(c->b) +
                 (c->a * c->b < 0 ? " (a b < 0)" : " (a b > 0)");
      }
    } else if (e.type == "CP") {
      if (const auto c = detail::cusp_coefficient(system_, p, e.at.state)) {
        e.coefficients = {{"c", *c}};
        e.note = "c = " + format_double(*c);
      }
    } else if (e.type == "ZH") {
      if (const auto z = detail::zero_hopf_coefficients(system_, p, e.at.state)) {
        e.coefficients = {{"b", z->b}, {"c", z->c}, {"a", z->a}, {"s", z->s}, {"theta", z->theta}};
        e.note = "s = " + format_number(z->s) + ", theta = " + format_number(z->theta);
      }
    } else if (e.type == "HH" && e.at.kappa > 0.0) {
      if (const auto h =
              detail::double_hopf_coefficients(system_, p, e.at.state, std::sqrt(e.at.kappa))) {
        e.coefficients = {{"p11", h->p11}, {"p12", h->p12},     {"p21", h->p21},
                          {"p22", h->p22}, {"theta", h->theta}, {"delta", h->delta}};
        e.note = "p11 p22 " + std::string(h->p11 * h->p22 > 0 ? "> 0" : "< 0") +
                 ", theta = " + format_number(h->theta) + ", delta = " + format_number(h->delta);
      }
    } else if (e.type == "GH" && e.at.kappa > 0.0) {
      if (const auto l2 =
              detail::second_lyapunov_coefficient(system_, p, e.at.state, std::sqrt(e.at.kappa))) {
        e.coefficients = {{"l2", *l2}};
        e.note =
            "l2 = " + format_number(*l2) +
            (*l2 < 0 ? " (a fold of cycles where l1 > 0)" : " (a fold of cycles where l1 < 0)");
      } else {
        e.note = "l2 needs f's fifth derivatives, which this system does not give";
      }
    }
  }

  // The user values passed between a and b, each solved with its parameter held there (from the
  // point interpolated linearly between them).
  void user_points(const Point& a, const Point& b, driver::Found<Event>& found) const {
    const Eigen::VectorXd ya = y_of(a), yb = y_of(b);
    for (const auto& v : o_.user_values) {
      const int k = v.second ? n_ + 1 : n_;
      if (!((ya[k] - v.value) * (yb[k] - v.value) < 0.0 || yb[k] == v.value)) continue;
      const double w = (v.value - ya[k]) / (yb[k] - ya[k]);
      Event e;
      e.type = "UZ";
      const std::string name = system_.parameter_names()[v.second ? second_ : first_];
      e.note = (v.stop ? "stop at " : "user value ") + name + " = " + format_double(v.value);
      e.description = "the value asked for";
      e.after_point = a.index;
      e.arclength = w * b.step;
      std::string why;
      auto p = correct((1 - w) * ya + w * yb, Eigen::VectorXd::Unit(size_, k), v.value, a,
                       a.tangent, why);
      e.located = p.has_value();
      e.at = p ? *p : b;
      if (!p) e.note += "; not located: " + why;
      e.first = e.at.first;
      e.second = e.at.second;
      found.events.push_back(std::move(e));
    }
  }

  std::vector<std::pair<std::string, std::string>> tests() const {
    if (hopf_)
      return {{"BT", "Bogdanov-Takens: omega -> 0, the Hopf curve turns into neutral saddles"},
              {"GH", "generalized Hopf: l1 = 0, the Hopf point turns subcritical"},
              {"ZH", "zero-Hopf: a real eigenvalue at zero beside the pair"},
              {"HH", "double Hopf: a second pair on the imaginary axis"}};
    return {{"BT", "Bogdanov-Takens: the zero eigenvalue is double"},
            {"CP", "cusp: the fold's quadratic coefficient vanishes"},
            {"ZH", "zero-Hopf: a pair on the imaginary axis beside the zero eigenvalue"}};
  }

  // The eigenvalues other than the k nearest `target`s (the curve's critical ones).
  Eigen::VectorXcd others(const Point& p) const {
    std::vector<Complex> rest(p.eigenvalues.data(), p.eigenvalues.data() + n_);
    std::vector<Complex> critical;
    if (hopf_) {
      const Complex root = std::sqrt(Complex(-p.kappa, 0.0));  // i omega, or k
      critical = {root, -root};
    } else {
      critical = {0.0};
    }
    for (const Complex c : critical) {
      auto it = std::min_element(rest.begin(), rest.end(), [&](Complex x, Complex y) {
        return std::abs(x - c) < std::abs(y - c);
      });
      if (it != rest.end()) rest.erase(it);
    }
    return Eigen::Map<Eigen::VectorXcd>(rest.data(), static_cast<Eigen::Index>(rest.size()));
  }
  // The product of the real parts of the complex pairs (upper halves) among `l`.
  static double pair_product(const Eigen::VectorXcd& l) {
    const double size = std::max(1.0, l.size() ? l.cwiseAbs().maxCoeff() : 0.0);
    double product = 1.0;
    for (const auto& x : l)
      if (x.imag() > 1e-9 * size) product *= x.real();
    return product;
  }

  // A test function's value at p, with the borders of the step's start a (continuous across
  // the step).
  double test_value(const std::string& type, const Point& p, const Point& a) const {
    const Eigen::VectorXd y = y_of(p);
    if (hopf_) {
      if (type == "BT") return p.kappa;
      if (type == "GH") return p.kappa > 0.0 ? p.lyapunov : std::nan("");
      if (type == "ZH") return a_of(y).determinant() / p.kappa;
      return pair_product(others(p));  // HH
    }
    if (type == "ZH") return pair_product(others(p));
    const Bordered b = bordered(a_of(y), a);
    const Eigen::VectorXd v = b.v.col(0).normalized(), w = b.w.col(0).normalized();
    if (type == "BT") return w.dot(v);
    // CP: <w, f_xx[v, v]>, f_xx[v, v] by central differences of the exact f_x along v.
    const double h = 1e-5 * std::max(1.0, y.head(n_).lpNorm<Eigen::Infinity>());
    Eigen::VectorXd up = y, down = y;
    up.head(n_) += h * v;
    down.head(n_) -= h * v;
    return w.dot((a_of(up) - a_of(down)) * v / (2 * h));
  }

  const OdeSystem& system_;
  bool hopf_;
  int first_, second_;
  ParameterValues base_;
  const EquilibriumCurveOptions& o_;
  std::optional<std::pair<double, double>> start_;  // the curve's first point's parameters
  int n_, size_, equations_;
  double scale_ = 0.0, kappa_scale_ = 0.0;
  Eigen::VectorXd weights_;
};

}  // namespace

namespace {

// `scales`: the state's and kappa's sizes to scale the arclength by at least (a switch at a
// codimension-two point at the origin: the curve it came from), else those of the start.
EquilibriumCurve start_curve(const OdeSystem& system, EquilibriumEventType kind, int first,
                             int second, const ParameterValues& base, const Eigen::VectorXd& state,
                             double kappa, const std::string& origin,
                             EquilibriumCurveOptions options,
                             const EquilibriumCurveCallbacks& callbacks,
                             std::pair<double, double> scales = {0.0, 0.0}) {
  const Stopwatch started;
  const bool hopf = kind == EquilibriumEventType::Hopf;
  const double p1 = system.parameter(base, first), p2 = system.parameter(base, second);
  if (p1 < options.first_lower || p1 > options.first_upper || p2 < options.second_lower ||
      p2 > options.second_upper)
    throw std::invalid_argument("the window does not hold the event (" +
                                system.parameter_names()[first] + " = " + format_double(p1) + ", " +
                                system.parameter_names()[second] + " = " + format_double(p2) + ")");
  EquilibriumCurve curve;
  curve.kind = kind;
  curve.first = first;
  curve.second = second;
  curve.first_name = system.parameter_names()[first];
  curve.second_name = system.parameter_names()[second];
  curve.state_names = system.state_names();
  curve.start_values = base;
  curve.options = options;
  curve.origin = origin;
  const int n = system.dimension();

  CurveProblem probe(system, hopf, first, second, base, options);
  Eigen::VectorXd y0(probe.size());
  y0.head(n) = state;
  y0[n] = p1;
  y0[n + 1] = p2;
  if (hopf)
    y0[n + 2] = kappa;
  else
    kappa = 0.0;
  probe.widen_scale(state, kappa);
  probe.widen_scale(scales.first, scales.second);
  // The event corrected onto the augmented system with a parameter held: the second, unless the
  // curve moves less in it than in the first (at a codimension-two switch the new curve may lie
  // in a level of the second: the double Hopf form's other Hopf curve is b2 = 0). The curve's
  // direction from its null vector, oriented by the second parameter where it moves in it.
  Point borders;
  probe.renew(borders, y0);
  std::string why;
  const Eigen::MatrixXd j0 = probe.jacobian(y0, borders);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(j0, Eigen::ComputeFullV);
  Eigen::VectorXd along = svd.matrixV().col(probe.size() - 1);
  const double moves1 = std::abs(along[n] * probe.weights()[n]);
  const double moves2 = std::abs(along[n + 1] * probe.weights()[n + 1]);
  const int held = moves2 >= 0.1 * moves1 ? n + 1 : n;
  if (along[held] < 0.0) along = -along;
  auto start =
      probe.correct(y0, Eigen::VectorXd::Unit(probe.size(), held), y0[held], borders, along, why);
  if (!start) {
    curve.stop = StopReason::StartFailed;
    curve.stop_reason = "the event could not be corrected onto the curve's system: " + why;
    curve.seconds = started.seconds();
    return curve;
  }
  probe.renew(*start, probe.y_of(*start));
  start->index = 0;

  using Result = driver::Result<Point, Event>;
  driver::Options d = driver::step_options(options);
  d.location_retries = 2;
  d.rule = {3, 2.0, 2.0, 6, 0.5};  // Newton: few iterations, a doubled step
  const auto half = [&](int direction) {
    CurveProblem run(system, hopf, first, second, base, options);
    run.widen_scale(start->state, start->kappa);
    run.widen_scale(scales.first, scales.second);
    run.set_start(*start);
    Point from = *start;
    from.tangent = run.tangent(run.jacobian(run.y_of(from), from), direction * along);
    driver::Callbacks<Point, Event> cb;
    if (callbacks.on_point)
      cb.on_point = [&](const Point& p) {
        if (p.index == 0) return;  // the start is reported once
        Point q = p;
        q.index *= direction;
        callbacks.on_point(q);
      };
    cb.on_event = callbacks.on_event;
    cb.stop_requested = callbacks.stop_requested;
    return driver::continuation(run, std::move(from), d, cb);
  };
  if (callbacks.on_point) callbacks.on_point(*start);
  Result forward = half(+1);
  Result joined = forward.stop == driver::Stop::Interrupted
                      ? std::move(forward)
                      : driver::join(half(-1), std::move(forward));
  curve.points = std::move(joined.points);
  curve.events = std::move(joined.events);
  curve.stop = joined.stop;
  curve.backward_stop = joined.backward_stop;
  curve.stop_reason = std::move(joined.message);
  curve.seconds = started.seconds();
  return curve;
}

}  // namespace

EquilibriumCurve continue_equilibrium_curve(const OdeSystem& system,
                                            const EquilibriumBranch& branch,
                                            const EquilibriumEvent& event, int second,
                                            EquilibriumCurveOptions options,
                                            const EquilibriumCurveCallbacks& callbacks) {
  const bool hopf = event.type == EquilibriumEventType::Hopf;
  if (!hopf && event.type != EquilibriumEventType::Fold)
    throw std::invalid_argument(
        "a curve of equilibria starts at a fold (LP) or a Hopf point (HB), "
        "not at " +
        to_string(event.type));
  const int first = branch.parameter;
  if (second < 0 || second >= system.parameter_count())
    throw std::invalid_argument("second: expected the index of a named parameter");
  if (second == first)
    throw std::invalid_argument("the second parameter is the branch's own (" +
                                branch.parameter_name + "); expected another");
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  const ParameterValues base = system.with_parameter(branch.start_values, first, event.parameter);
  double kappa = std::nan("");
  if (hopf) {
    // omega^2 from the event's pair (its Hopf description, or the eigenvalue nearest the axis).
    double omega = event.hopf ? event.hopf->omega : 0.0;
    if (!(omega > 0.0))
      for (const auto& l : event.eigenvalues)
        if (l.imag() > 0 && (omega == 0.0 || std::abs(l.real()) < 1e-3)) omega = l.imag();
    kappa = omega * omega;
  }
  return start_curve(system, event.type, first, second, base, event.state, kappa,
                     to_string(event.type) + " at " + branch.parameter_name + " = " +
                         format_double(event.parameter),
                     std::move(options), callbacks);
}

CodimensionTwoPoint codimension_two_point(const OdeSystem& system, const EquilibriumCurve& curve,
                                          const EquilibriumCurveEvent& event) {
  CodimensionTwoPoint p;
  p.type = event.type;
  p.on = curve.kind;
  p.first = curve.first;
  p.second = curve.second;
  p.values =
      system.with_parameter(system.with_parameter(curve.start_values, curve.first, event.first),
                            curve.second, event.second);
  p.state = event.at.state;
  p.kappa = event.at.kappa;
  for (const auto& q : curve.points) {
    p.state_scale = std::max(p.state_scale, q.state.lpNorm<Eigen::Infinity>());
    if (std::isfinite(q.kappa)) p.kappa_scale = std::max(p.kappa_scale, std::abs(q.kappa));
  }
  return p;
}

CurveFromCodimensionTwo curve_from_codimension_two(const OdeSystem& system,
                                                   const CodimensionTwoPoint& point) {
  const bool on_hopf = point.on == EquilibriumEventType::Hopf;
  CurveFromCodimensionTwo next;
  if (point.type == "BT" || point.type == "ZH")
    next.kind = on_hopf ? EquilibriumEventType::Fold : EquilibriumEventType::Hopf;
  else if (point.type == "HH" && on_hopf)
    next.kind = EquilibriumEventType::Hopf;
  else if (point.type == "CP" && !on_hopf)
    next.kind = EquilibriumEventType::Fold;
  else
    throw std::invalid_argument(
        "a curve of equilibria switches at a BT, ZH or CP of a fold curve, or at a BT, ZH or HH "
        "of a Hopf curve; not at " +
        point.type + " of a " + (on_hopf ? "Hopf" : "fold") + " curve");
  const int count = system.parameter_count();
  if (point.first < 0 || point.first >= count || point.second < 0 || point.second >= count ||
      point.first == point.second)
    throw std::invalid_argument("expected two different parameters");
  if (point.state.size() != system.dimension())
    throw std::invalid_argument("the point's state has the wrong size");
  // The new Hopf curve's omega^2: 0 at BT (its Hopf part on one side, neutral saddles on the
  // other); at ZH the pair's; at HH the pair that is not the old curve's.
  if (next.kind == EquilibriumEventType::Hopf && point.type != "BT") {
    Eigen::MatrixXd a;
    system.jacobian(0.0, point.state.data(), point.values.data(), a);
    // Nearest the axis, and (HH) away from the old pair: their frequencies differ.
    const double old_omega = on_hopf && point.kappa > 0.0 ? std::sqrt(point.kappa) : 0.0;
    const double omega = detail::pair_frequency(a, old_omega);
    if (!(omega > 0.0))
      throw std::invalid_argument("no pair of eigenvalues for the Hopf curve at the " + point.type +
                                  " point");
    next.kappa = omega * omega;
  } else if (next.kind == EquilibriumEventType::Hopf) {
    next.kappa = 0.0;
  }
  return next;
}

EquilibriumCurve continue_from_codimension_two(const OdeSystem& system,
                                               const CodimensionTwoPoint& point,
                                               EquilibriumCurveOptions options,
                                               const EquilibriumCurveCallbacks& callbacks) {
  const CurveFromCodimensionTwo next = curve_from_codimension_two(system, point);
  if (auto wrong = options.validate()) throw std::invalid_argument(wrong->message());
  const auto names = system.parameter_names();
  return start_curve(
      system, next.kind, point.first, point.second, point.values, point.state, next.kappa,
      point.type + " at " + names[point.first] + " = " +
          format_double(system.parameter(point.values, point.first)) + ", " + names[point.second] +
          " = " + format_double(system.parameter(point.values, point.second)),
      std::move(options), callbacks,
      // At least 1 for the state: a codimension-two point often sits where a
      // state is 0 (the BT form's BT, on a Hopf curve all at x = 0), and a scale
      // of 1e-3 there made the fold curve from it 311 points, against 59 from
      // the equilibria's own fold.
      {std::max(1.0, point.state_scale), point.kappa_scale});
}

}  // namespace sympathy
