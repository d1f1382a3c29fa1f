// The trajectory fit (see trajectory_fit.hpp). About 680 lines in one file: the residual evaluator,
// the NLopt stages, the Levenberg-Marquardt polish and the statistics at the optimum all work on
// one Evaluator and its scaled unknowns; each is a section below, in the order a fit runs them.
#include "sympathy/core/trajectory_fit.hpp"

#include <nlopt.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "sympathy/core/text.hpp"

namespace sympathy {

std::string to_string(LocalMethod m) {
  switch (m) {
    case LocalMethod::Slsqp:
      return "NLopt SLSQP";
    case LocalMethod::Lbfgs:
      return "NLopt L-BFGS";
    case LocalMethod::Mma:
      return "NLopt MMA";
    case LocalMethod::Bobyqa:
      return "NLopt BOBYQA";
    case LocalMethod::NelderMead:
      return "NLopt Nelder-Mead";
    case LocalMethod::LevenbergMarquardt:
      return "Levenberg-Marquardt";
  }
  return "?";
}

std::string to_string(GlobalMethod m) {
  switch (m) {
    case GlobalMethod::None:
      return "none";
    case GlobalMethod::ControlledRandomSearch:
      return "NLopt CRS2 (controlled random search)";
    case GlobalMethod::Direct:
      return "NLopt DIRECT-L";
    case GlobalMethod::Isres:
      return "NLopt ISRES";
    case GlobalMethod::Mlsl:
      return "NLopt MLSL (multi-start, low-discrepancy starts, SLSQP)";
  }
  return "?";
}

namespace {

// Rows of the residual vector: (sample, column) pairs, the initial time's fixed ones left out.
struct ResidualLayout {
  std::vector<int> row_of;  // per sample * columns + column: its row, or -1
  int rows = 0;
};

ResidualLayout layout(const TrajectoryFitProblem& pb) {
  const int n = static_cast<int>(pb.times.size());
  const int m = static_cast<int>(pb.observed.size());
  ResidualLayout l;
  l.row_of.assign(static_cast<std::size_t>(n) * m, -1);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < m; ++k) {
      const bool free_at_start =
          std::any_of(pb.initial.begin(), pb.initial.end(),
                      [&](const FreeInitial& f) { return f.component == pb.observed[k]; });
      if (i == 0 && !free_at_start) continue;
      l.row_of[static_cast<std::size_t>(i) * m + k] = l.rows++;
    }
  return l;
}

// The residuals and their Jacobian as functions of the scaled unknowns u.
class Evaluator {
 public:
  Evaluator(const OdeSystem& system, const TrajectoryFitProblem& pb, const FlowOptions& flow,
            const std::function<bool()>* stop = nullptr)
      : system_(system), pb_(pb), flow_(system, flow), layout_(layout(pb)), stop_(stop) {
    for (const auto& f : pb.parameters) {
      parameter_indices_.push_back(f.index);
      start_.push_back(system.parameter(pb.parameter_values, f.index));
    }
    for (const auto& f : pb.initial) {
      initial_components_.push_back(f.component);
      start_.push_back(pb.initial_state[f.component]);
    }
    scale_ = pb.column_scale.size() ? pb.column_scale
                                    : Eigen::VectorXd::Ones(static_cast<int>(pb.observed.size()));
  }

  int unknowns() const { return static_cast<int>(start_.size()); }
  int rows() const { return layout_.rows; }
  int parameter_count() const { return static_cast<int>(parameter_indices_.size()); }

  // Physical value of each unknown.
  Eigen::VectorXd physical(const Eigen::VectorXd& u) const {
    Eigen::VectorXd v(unknowns());
    for (int j = 0; j < unknowns(); ++j) v[j] = to_physical(j, u[j]);
    return v;
  }
  double to_physical(int j, double u) const {
    if (j < parameter_count()) {
      const auto& f = pb_.parameters[j];
      return f.logarithmic ? start_[j] * std::exp(u) : start_[j] + f.scale * u;
    }
    return start_[j] + pb_.initial[j - parameter_count()].scale * u;
  }
  double to_scaled(int j, double v) const {
    if (j < parameter_count()) {
      const auto& f = pb_.parameters[j];
      if (f.logarithmic) return v > 0.0 ? std::log(v / start_[j]) : -kInfinity;
      return (v - start_[j]) / f.scale;
    }
    return (v - start_[j]) / pb_.initial[j - parameter_count()].scale;
  }
  // d(physical)/du.
  Eigen::VectorXd chain(const Eigen::VectorXd& u) const {
    Eigen::VectorXd d(unknowns());
    for (int j = 0; j < unknowns(); ++j) {
      if (j < parameter_count()) {
        const auto& f = pb_.parameters[j];
        d[j] = f.logarithmic ? to_physical(j, u[j]) : f.scale;
      } else {
        d[j] = pb_.initial[j - parameter_count()].scale;
      }
    }
    return d;
  }

  // Whether the caller asked the fit to stop (asked before each integration; once true, true).
  bool stopping() {
    if (!interrupted_ && stop_ && *stop_ && (*stop_)()) interrupted_ = true;
    return interrupted_;
  }
  bool interrupted() const { return interrupted_; }

  // Residuals at u, and the Jacobian if `jacobian` is given. False if the integration failed.
  bool evaluate(const Eigen::VectorXd& u, Eigen::VectorXd& r, Eigen::MatrixXd* jacobian) {
    ++evaluations_;
    if (jacobian) ++jacobian_evaluations_;
    const Eigen::VectorXd v = physical(u);
    if (!v.allFinite()) return false;
    const ParameterValues p = parameter_values(u);
    Eigen::VectorXd z0 = pb_.initial_state;
    for (std::size_t l = 0; l < initial_components_.size(); ++l)
      z0[initial_components_[l]] = v[parameter_count() + static_cast<int>(l)];
    const int m = static_cast<int>(pb_.observed.size());
    const int ni = static_cast<int>(initial_components_.size());
    r.resize(rows());
    Eigen::VectorXd d;
    if (jacobian) {
      jacobian->setZero(rows(), unknowns());
      d = chain(u);
    }
    std::size_t i = 0;
    try {
      if (jacobian) {
        flow_.sample_with_sensitivities(
            z0, p, pb_.times.front(), pb_.times, initial_components_, parameter_indices_,
            [&](double, const Eigen::VectorXd& z, const Eigen::MatrixXd& S) {
              for (int k = 0; k < m; ++k) {
                const int row = layout_.row_of[i * m + k];
                if (row < 0) continue;
                const int c = pb_.observed[k];
                r[row] = (z[c] - pb_.values(static_cast<int>(i), k)) / scale_[k];
                for (int j = 0; j < parameter_count(); ++j)
                  (*jacobian)(row, j) = S(c, ni + j) * d[j] / scale_[k];
                for (int l = 0; l < ni; ++l)
                  (*jacobian)(row, parameter_count() + l) =
                      S(c, l) * d[parameter_count() + l] / scale_[k];
              }
              ++i;
            });
      } else {
        flow_.sample(z0, p, pb_.times.front(), pb_.times, [&](double, const Eigen::VectorXd& z) {
          for (int k = 0; k < m; ++k) {
            const int row = layout_.row_of[i * m + k];
            if (row >= 0)
              r[row] = (z[pb_.observed[k]] - pb_.values(static_cast<int>(i), k)) / scale_[k];
          }
          ++i;
        });
      }
    } catch (const IntegrationError&) {
      return false;
    }
    return r.allFinite() && (!jacobian || jacobian->allFinite());
  }

  // The sum of squares, HUGE_VAL where the integration fails; remembers the best point.
  double rss(const Eigen::VectorXd& u, Eigen::VectorXd* gradient) {
    Eigen::VectorXd r;
    Eigen::MatrixXd J;
    const bool ok = evaluate(u, r, gradient ? &J : nullptr);
    if (!ok) {
      if (gradient) gradient->setZero(unknowns());
      return HUGE_VAL;
    }
    const double f = r.squaredNorm();
    if (gradient) *gradient = 2.0 * J.transpose() * r;
    if (f < best_rss_) {
      best_rss_ = f;
      best_u_ = u;
    }
    return f;
  }

  // The problem's parameter values with the free ones at u.
  ParameterValues parameter_values(const Eigen::VectorXd& u) const {
    const Eigen::VectorXd v = physical(u);
    ParameterValues p = pb_.parameter_values;
    for (int j = 0; j < parameter_count(); ++j)
      system_.set_parameter(p, parameter_indices_[j], v[j]);
    return p;
  }

  double best_rss() const { return best_rss_; }
  const Eigen::VectorXd& best_u() const { return best_u_; }
  void reset_best() { best_rss_ = HUGE_VAL; }
  int evaluations() const { return evaluations_; }
  int jacobian_evaluations() const { return jacobian_evaluations_; }
  const Eigen::VectorXd& column_scale() const { return scale_; }
  const Flow& flow() const { return flow_; }

 private:
  const OdeSystem& system_;
  const TrajectoryFitProblem& pb_;
  Flow flow_;
  ResidualLayout layout_;
  std::vector<int> parameter_indices_;
  std::vector<int> initial_components_;
  std::vector<double> start_;
  Eigen::VectorXd scale_;
  int evaluations_ = 0;
  int jacobian_evaluations_ = 0;
  const std::function<bool()>* stop_ = nullptr;  // the options' stop_requested
  bool interrupted_ = false;
  double best_rss_ = HUGE_VAL;
  Eigen::VectorXd best_u_;
};

std::string format_tolerance(double v) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", v);
  return buffer;
}

struct Bounds {
  Eigen::VectorXd lower, upper;  // scaled
  Eigen::VectorXd clamp(const Eigen::VectorXd& u) const {
    return u.cwiseMax(lower).cwiseMin(upper);
  }
};

// Where a local method ends: the point, its residuals and Jacobian, and why it stopped.
struct LocalOutcome {
  Eigen::VectorXd u, r;
  Eigen::MatrixXd J;
  bool converged = false;
  std::string reason;
};

// Levenberg-Marquardt with Marquardt's diagonal scaling and Nielsen's damping update. Every
// trial point is evaluated with its Jacobian (one integration), so an accepted step needs no
// second one.
// `at_u`: the residuals and Jacobian at u when already integrated (nothing to integrate again).
LocalOutcome levenberg_marquardt(Evaluator& ev, Eigen::VectorXd u, const Bounds& bounds,
                                 const TrajectoryFitOptions& o,
                                 const LocalOutcome* at_u = nullptr) {
  LocalOutcome out;
  const int first = ev.evaluations();
  if (at_u) {
    out.r = at_u->r;
    out.J = at_u->J;
  } else if (!ev.evaluate(u, out.r, &out.J)) {
    throw IntegrationError("the trajectory cannot be integrated at the starting values", 0.0);
  }
  double rss = out.r.squaredNorm();
  double lambda = 1e-3;
  double nu = 2.0;
  int rejections = 0;  // in a row
  Eigen::VectorXd r_new;
  Eigen::MatrixXd J_new;
  while (true) {
    const Eigen::MatrixXd A = out.J.transpose() * out.J;
    const Eigen::VectorXd g = out.J.transpose() * out.r;
    const Eigen::VectorXd D =
        A.diagonal().cwiseMax(std::max(A.diagonal().maxCoeff(), 1e-300) * 1e-12);
    // First-order optimality: the decrease the undamped Gauss-Newton step promises.
    Eigen::MatrixXd K = A;
    K.diagonal() += 1e-12 * D;
    const Eigen::VectorXd gn = K.ldlt().solve(-g);
    const double promised = -g.dot(gn);
    if (promised <= o.rss_tolerance * rss) {
      out.converged = true;
      out.reason = std::string("optimal: Gauss-Newton promises a relative decrease below ") +
                   format_tolerance(o.rss_tolerance);
      break;
    }
    // The step left, in standard errors: promised = |J gn|^2 = gn^T (J^T J) gn, over s^2.
    const double s2 = rss / static_cast<double>(out.r.size() - u.size());
    if (s2 > 0.0 && promised <= o.offset_tolerance * o.offset_tolerance * s2) {
      out.converged = true;
      out.reason = std::string("optimal: the Gauss-Newton step left is below ") +
                   format_tolerance(o.offset_tolerance) + " standard errors";
      break;
    }
    if (ev.stopping()) {
      out.reason = "interrupted";
      break;
    }
    if (ev.evaluations() - first >= o.max_evaluations) {
      out.reason =
          std::string("evaluation limit reached (") + std::to_string(o.max_evaluations) + ")";
      break;
    }
    // Where the model fits the data to the integration's accuracy (scaled residuals below 1e3
    // rtol), the sum of squares is the integration's own error, which no step lowers reliably:
    // stop after a few failures to lower it there.
    const double floor = 1e3 * o.flow.rtol;
    if (rejections >= 3 && rss <= floor * floor * static_cast<double>(out.r.size())) {
      out.converged = true;
      out.reason =
          "at the optimum to the integration's accuracy (residuals below 1e3 rtol; 3 steps "
          "in a row raised the sum of squares)";
      break;
    }
    if (lambda > 1e12) {
      out.converged = true;
      out.reason = "no step lowers the sum of squares further (integration accuracy)";
      break;
    }
    K = A;
    K.diagonal() += lambda * D;
    Eigen::VectorXd step = bounds.clamp(u + K.ldlt().solve(-g)) - u;
    if (step.cwiseAbs().maxCoeff() <= o.step_tolerance) {
      out.converged = true;
      out.reason = std::string("step below ") + format_tolerance(o.step_tolerance);
      break;
    }
    const double predicted = -(2.0 * g.dot(step) + step.dot(A * step));
    const Eigen::VectorXd u_new = u + step;
    const bool ok = ev.evaluate(u_new, r_new, &J_new);
    const double rss_new = ok ? r_new.squaredNorm() : HUGE_VAL;
    if (ok && rss_new < rss) {
      const double rho = predicted > 0.0 ? (rss - rss_new) / predicted : 0.0;
      const double decrease = rss - rss_new;
      u = u_new;
      out.r = r_new;
      out.J = J_new;
      rss = rss_new;
      lambda *= std::max(1.0 / 3.0, 1.0 - std::pow(2.0 * std::min(rho, 1.0) - 1.0, 3));
      nu = 2.0;
      rejections = 0;
      if (decrease <= o.rss_tolerance * rss) {
        out.converged = true;
        out.reason = std::string("relative decrease of the sum of squares below ") +
                     format_tolerance(o.rss_tolerance);
        break;
      }
    } else {
      lambda *= nu;
      nu *= 2.0;
      ++rejections;
    }
  }
  out.u = u;
  return out;
}

nlopt::algorithm nlopt_local(LocalMethod m) {
  switch (m) {
    case LocalMethod::Slsqp:
      return nlopt::LD_SLSQP;
    case LocalMethod::Lbfgs:
      return nlopt::LD_LBFGS;
    case LocalMethod::Mma:
      return nlopt::LD_MMA;
    case LocalMethod::Bobyqa:
      return nlopt::LN_BOBYQA;
    case LocalMethod::NelderMead:
      return nlopt::LN_NELDERMEAD;
    case LocalMethod::LevenbergMarquardt:
      break;
  }
  throw std::logic_error("not an NLopt local method");
}

std::string describe(nlopt::result r, const TrajectoryFitOptions& o, int max_evaluations) {
  switch (r) {
    case nlopt::SUCCESS:
      return "NLopt reports success";
    case nlopt::STOPVAL_REACHED:
      return "stop value reached";
    case nlopt::FTOL_REACHED:
      return std::string("relative change of the sum of squares below ") +
             format_tolerance(o.rss_tolerance);
    case nlopt::XTOL_REACHED:
      return std::string("step below ") + format_tolerance(o.step_tolerance);
    case nlopt::MAXEVAL_REACHED:
      return std::string("evaluation limit reached (") + std::to_string(max_evaluations) + ")";
    case nlopt::MAXTIME_REACHED:
      return "time limit reached";
    default:
      return std::string("NLopt result ") + std::to_string(static_cast<int>(r));
  }
}

// The sum of squares relative to a reference (1 at the start), for NLopt.
struct NloptObjective {
  Evaluator* ev;
  double reference;
  static double call(const std::vector<double>& x, std::vector<double>& grad, void* data) {
    auto* self = static_cast<NloptObjective*>(data);
    if (self->ev->stopping()) throw nlopt::forced_stop();  // NLopt ends and rethrows it
    const Eigen::Map<const Eigen::VectorXd> u(x.data(), static_cast<int>(x.size()));
    if (grad.empty()) return self->ev->rss(u, nullptr) / self->reference;
    Eigen::VectorXd g;
    const double f = self->ev->rss(u, &g);
    for (std::size_t j = 0; j < grad.size(); ++j)
      grad[j] = g[static_cast<int>(j)] / self->reference;
    return f / self->reference;
  }
};

// Runs an NLopt optimizer from u; returns the best point seen and why it stopped.
std::pair<Eigen::VectorXd, std::string> run_nlopt(nlopt::opt& opt, Evaluator& ev,
                                                  const Eigen::VectorXd& u0, double reference,
                                                  const TrajectoryFitOptions& o,
                                                  int max_evaluations, bool* converged) {
  NloptObjective objective{&ev, reference};
  opt.set_min_objective(NloptObjective::call, &objective);
  std::vector<double> x(u0.data(), u0.data() + u0.size());
  double f = 0.0;
  ev.reset_best();
  std::string reason;
  *converged = false;
  try {
    const nlopt::result r = opt.optimize(x, f);
    reason = describe(r, o, max_evaluations);
    *converged = r == nlopt::SUCCESS || r == nlopt::FTOL_REACHED || r == nlopt::XTOL_REACHED;
  } catch (const nlopt::roundoff_limited&) {
    reason = "NLopt: limited by roundoff (at the optimum within integration accuracy)";
    *converged = true;
  } catch (const nlopt::forced_stop&) {
    reason = ev.interrupted() ? "interrupted" : "NLopt: forced stop";
  } catch (const std::runtime_error& e) {
    reason = std::string("NLopt failed: ") + e.what();
  }
  if (ev.best_rss() == HUGE_VAL) {
    if (ev.interrupted()) return {u0, reason};  // stopped before its first point
    throw IntegrationError("the trajectory could not be integrated at any point the fit tried",
                           0.0);
  }
  return {ev.best_u(), reason};
}

}  // namespace

int residual_count(const TrajectoryFitProblem& problem) {
  return layout(problem).rows;
}

TrajectoryFitResult fit_trajectory(const OdeSystem& system, const TrajectoryFitProblem& pb,
                                   const TrajectoryFitOptions& o) {
  const Stopwatch t_start;
  // Check the problem.
  const int n = system.dimension();
  const int samples = static_cast<int>(pb.times.size());
  const int m = static_cast<int>(pb.observed.size());
  const int parameter_count = system.parameter_count();
  auto fail = [](const std::string& what) {
    throw std::invalid_argument(std::string("trajectory fit: ").append(what));
  };
  if (samples < 2) fail("needs at least two samples");
  for (int i = 0; i < samples; ++i)
    if (!std::isfinite(pb.times[i]) || (i > 0 && !(pb.times[i] > pb.times[i - 1])))
      fail("sample times must be finite and strictly increasing");
  if (m == 0) fail("no observed component");
  for (int c : pb.observed)
    if (c < 0 || c >= n) fail("observed component out of range");
  if (pb.values.rows() != samples || pb.values.cols() != m || !pb.values.allFinite())
    fail("values must be finite, one row per sample and one column per observed component");
  if (pb.column_scale.size() != 0 &&
      (pb.column_scale.size() != m || !(pb.column_scale.array() > 0.0).all()))
    fail("column scales must be positive, one per observed component");
  if (pb.initial_state.size() != n || !pb.initial_state.allFinite())
    fail("the initial state must be finite, with one entry per state component");
  if (pb.parameters.empty() && pb.initial.empty()) fail("nothing to fit");
  if (pb.parameter_values.size() != system.parameter_values_size() ||
      !pb.parameter_values.allFinite())
    fail("the parameter values must be finite, as many as the system has");
  for (std::size_t j = 0; j < pb.parameters.size(); ++j) {
    const auto& f = pb.parameters[j];
    if (f.index < 0 || f.index >= parameter_count) fail("parameter index out of range");
    for (std::size_t i = 0; i < j; ++i)
      if (pb.parameters[i].index == f.index) fail("a parameter is free twice");
    const double v = system.parameter(pb.parameter_values, f.index);
    if (f.logarithmic && !(v > 0.0))
      fail(std::string("the logarithmically scaled parameter ") +
           system.parameter_names()[f.index] + " needs a positive starting value");
    if (!f.logarithmic && !(f.scale > 0.0)) fail("parameter scales must be positive");
    if (!(f.lower <= v && v <= f.upper))
      fail(std::string("the starting value of ") + system.parameter_names()[f.index] +
           " is outside its bounds");
  }
  for (std::size_t j = 0; j < pb.initial.size(); ++j) {
    const auto& f = pb.initial[j];
    if (f.component < 0 || f.component >= n) fail("initial component out of range");
    for (std::size_t i = 0; i < j; ++i)
      if (pb.initial[i].component == f.component) fail("an initial component is free twice");
    if (!(f.scale > 0.0)) fail("initial scales must be positive");
  }

  TrajectoryFitResult result;
  Evaluator ev(system, pb, o.flow, &o.stop_requested);
  const int p = ev.unknowns();
  result.unknowns = p;
  result.residuals = ev.rows();
  if (result.residuals <= p)
    fail(std::to_string(result.residuals) + " residuals for " + std::to_string(p) +
         " unknowns; expected more residuals than unknowns");

  Bounds bounds{Eigen::VectorXd::Constant(p, -kInfinity), Eigen::VectorXd::Constant(p, kInfinity)};
  for (int j = 0; j < static_cast<int>(pb.parameters.size()); ++j) {
    bounds.lower[j] = ev.to_scaled(j, pb.parameters[j].lower);
    bounds.upper[j] = ev.to_scaled(j, pb.parameters[j].upper);
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(p);
  result.start = ev.physical(u);

  // The start's residuals, with the Jacobian when Levenberg-Marquardt starts right there (no
  // global stage): it then takes over this integration instead of repeating it.
  const bool local_from_start =
      o.global == GlobalMethod::None && o.local == LocalMethod::LevenbergMarquardt;
  LocalOutcome at_start;
  const int before_start = ev.evaluations();
  if (!ev.evaluate(u, at_start.r, local_from_start ? &at_start.J : nullptr))
    throw IntegrationError("the trajectory cannot be integrated at the starting values", 0.0);
  result.rss_start = at_start.r.squaredNorm();
  const double reference = std::max(result.rss_start, 1e-300);
  double rss_now = result.rss_start;

  // Global stage.
  if (o.global != GlobalMethod::None) {
    const Stopwatch t0;
    const int before = ev.evaluations();
    Bounds box{Eigen::VectorXd(p), Eigen::VectorXd(p)};
    for (int j = 0; j < p; ++j) {
      const bool is_parameter = j < static_cast<int>(pb.parameters.size());
      const double lo = is_parameter ? pb.parameters[j].search_lower
                                     : pb.initial[j - pb.parameters.size()].search_lower;
      const double hi = is_parameter ? pb.parameters[j].search_upper
                                     : pb.initial[j - pb.parameters.size()].search_upper;
      box.lower[j] = std::max(ev.to_scaled(j, lo), bounds.lower[j]);
      box.upper[j] = std::min(ev.to_scaled(j, hi), bounds.upper[j]);
      if (!std::isfinite(box.lower[j]) || !std::isfinite(box.upper[j]) ||
          !(box.lower[j] < box.upper[j]))
        fail("the global stage needs a finite search box around each unknown");
    }
    nlopt::srand(o.seed);
    nlopt::algorithm algorithm = nlopt::GN_CRS2_LM;
    if (o.global == GlobalMethod::Direct) algorithm = nlopt::GN_DIRECT_L;
    if (o.global == GlobalMethod::Isres) algorithm = nlopt::GN_ISRES;
    if (o.global == GlobalMethod::Mlsl) algorithm = nlopt::G_MLSL_LDS;
    nlopt::opt opt(algorithm, static_cast<unsigned>(p));
    opt.set_lower_bounds(std::vector<double>(box.lower.data(), box.lower.data() + p));
    opt.set_upper_bounds(std::vector<double>(box.upper.data(), box.upper.data() + p));
    opt.set_maxeval(o.global_evaluations);
    if (o.global == GlobalMethod::Mlsl) {
      nlopt::opt local(nlopt::LD_SLSQP, static_cast<unsigned>(p));
      local.set_ftol_rel(1e-4);
      local.set_maxeval(30);
      opt.set_local_optimizer(local);
    }
    bool converged = false;
    auto [best, reason] =
        run_nlopt(opt, ev, box.clamp(u), reference, o, o.global_evaluations, &converged);
    // The global stage only proposes a start: keep the starting values if they are better.
    if (ev.best_rss() < rss_now) {
      u = best;
      rss_now = ev.best_rss();
    }
    result.stages.push_back({"global", to_string(o.global), ev.evaluations() - before,
                             result.rss_start, rss_now, reason, t0.seconds()});
  }

  // Local stage, and the polish.
  LocalOutcome final;
  {
    const Stopwatch t0;
    // The start's integration is the local stage's first when it takes it over.
    const int before = local_from_start ? before_start : ev.evaluations();
    const double rss_before = rss_now;
    if (o.local == LocalMethod::LevenbergMarquardt) {
      final = levenberg_marquardt(ev, u, bounds, o, local_from_start ? &at_start : nullptr);
      result.stages.push_back({"local", to_string(o.local), ev.evaluations() - before, rss_before,
                               final.r.squaredNorm(), final.reason, t0.seconds()});
    } else {
      nlopt::opt opt(nlopt_local(o.local), static_cast<unsigned>(p));
      auto finite_or = [](double v, double inf) { return std::isfinite(v) ? v : inf; };
      std::vector<double> lo(p), hi(p);
      for (int j = 0; j < p; ++j) {
        lo[j] = finite_or(bounds.lower[j], -HUGE_VAL);
        hi[j] = finite_or(bounds.upper[j], HUGE_VAL);
      }
      opt.set_lower_bounds(lo);
      opt.set_upper_bounds(hi);
      opt.set_xtol_abs(o.step_tolerance);
      opt.set_ftol_rel(o.rss_tolerance);
      opt.set_maxeval(o.max_evaluations);
      if (o.local == LocalMethod::Bobyqa || o.local == LocalMethod::NelderMead)
        opt.set_initial_step(0.1);
      bool converged = false;
      auto [best, reason] = run_nlopt(opt, ev, u, reference, o, o.max_evaluations, &converged);
      if (ev.best_rss() < HUGE_VAL) {  // else interrupted before its first point: u stays
        u = best;
        rss_now = ev.best_rss();
      }
      result.stages.push_back({"local", to_string(o.local), ev.evaluations() - before, rss_before,
                               rss_now, reason, t0.seconds()});
      const Stopwatch t1;
      const int before_polish = ev.evaluations();
      if (o.polish) {
        final = levenberg_marquardt(ev, u, bounds, o);
        result.stages.push_back({"polish", "Gauss-Newton (Levenberg-Marquardt)",
                                 ev.evaluations() - before_polish, rss_now, final.r.squaredNorm(),
                                 final.reason, t1.seconds()});
      } else {
        final.u = u;
        final.converged = converged;
        final.reason = reason;
        if (!ev.evaluate(u, final.r, &final.J))
          throw IntegrationError("the trajectory cannot be integrated at the fitted values", 0.0);
      }
    }
  }
  result.fitted_parameters = ev.parameter_values(final.u);

  // Statistics at the optimum.
  result.values = ev.physical(final.u);
  result.rss = final.r.squaredNorm();
  result.interrupted = ev.interrupted();
  result.converged = final.converged && !result.interrupted;
  result.stop_reason = result.interrupted ? "interrupted" : final.reason;
  const int dof = result.residuals - p;
  result.sigma2 = result.rss / dof;
  const Eigen::VectorXd d = ev.chain(final.u);
  Eigen::VectorXd norms = final.J.colwise().norm();
  Eigen::MatrixXd Jn = final.J;
  for (int j = 0; j < p; ++j) Jn.col(j) /= norms[j] > 0.0 ? norms[j] : 1.0;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Jn, Eigen::ComputeThinV);
  const Eigen::VectorXd sv = svd.singularValues();
  const double largest = sv.size() ? sv[0] : 0.0;
  result.rank = 0;
  for (int i = 0; i < sv.size(); ++i)
    if (sv[i] > o.rank_tolerance * largest) ++result.rank;
  result.condition = sv[sv.size() - 1] > 0.0 ? largest / sv[sv.size() - 1] : kInfinity;
  Eigen::MatrixXd Cn = Eigen::MatrixXd::Zero(p, p);
  for (int i = 0; i < result.rank; ++i)
    Cn += svd.matrixV().col(i) * svd.matrixV().col(i).transpose() / (sv[i] * sv[i]);
  Eigen::VectorXd to_physical(p);
  for (int j = 0; j < p; ++j) to_physical[j] = d[j] / (norms[j] > 0.0 ? norms[j] : 1.0);
  result.covariance = result.sigma2 * to_physical.asDiagonal() * Cn * to_physical.asDiagonal();
  result.errors = result.covariance.diagonal().cwiseMax(0.0).cwiseSqrt();
  for (int i = result.rank; i < p; ++i) {
    std::vector<int> members;
    const double largest_component = svd.matrixV().col(i).cwiseAbs().maxCoeff();
    for (int j = 0; j < p; ++j)
      if (std::abs(svd.matrixV()(j, i)) > 1e-3 * largest_component || norms[j] == 0.0) {
        members.push_back(j);
        result.errors[j] = kInfinity;
      }
    result.undetermined.push_back(members);
  }
  result.correlation = Eigen::MatrixXd::Identity(p, p);
  for (int a = 0; a < p; ++a)
    for (int b = 0; b < p; ++b)
      if (a != b && std::isfinite(result.errors[a]) && std::isfinite(result.errors[b]) &&
          result.errors[a] > 0.0 && result.errors[b] > 0.0)
        result.correlation(a, b) = result.covariance(a, b) / (result.errors[a] * result.errors[b]);

  // Residual RMS per column, in the data's units.
  const ResidualLayout rows = layout(pb);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(m), count = Eigen::VectorXd::Zero(m);
  for (int i = 0; i < samples; ++i)
    for (int k = 0; k < m; ++k) {
      const int row = rows.row_of[static_cast<std::size_t>(i) * m + k];
      if (row < 0) continue;
      const double e = final.r[row] * ev.column_scale()[k];
      sum[k] += e * e;
      count[k] += 1.0;
    }
  result.column_rms = (sum.array() / count.array().max(1.0)).sqrt();

  result.evaluations = ev.evaluations();
  result.jacobian_evaluations = ev.jacobian_evaluations();
  result.statistics = ev.flow().statistics();
  result.seconds = t_start.seconds();
  return result;
}

}  // namespace sympathy
