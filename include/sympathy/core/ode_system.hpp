// The engine's view of a dynamical system z' = f(t, z; p).
//
// Everything above core (flows, shooting, Floquet, continuation) talks to this interface only;
// it knows nothing about metronomes. A system has named states and named parameters, a
// right-hand side, and its derivatives: the Jacobian df/dz, directional derivatives J*S for
// many columns at once (the variational equations), and df/dp for one named parameter.
#pragma once

#include <complex>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/low_rank_jacobian.hpp"

namespace sympathy {

// A state component near whose zero crossing the right-hand side changes steeply, within
// `width` of zero (e.g. an escapement switching with the sign of a pendulum's velocity).
// `scale` is a typical magnitude of the component away from the crossing. The flow resolves
// such crossings explicitly (see Flow) instead of trusting error control to notice them.
struct SteepZone {
  int component = 0;
  double width = 0.0;
  double scale = 1.0;
};

// A system's parameter values: a vector in the system's own layout (for a simple system one entry
// per named parameter; a model may hold more entries than it names, a name then setting several
// together). They travel with every call, as AUTO's PAR and BifurcationKit's `pars` do: nothing
// here stores the values a run uses, so one system object serves any number of runs at once.
using ParameterValues = Eigen::VectorXd;

class InvariantSubspace;

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;

  virtual int dimension() const = 0;
  virtual std::vector<std::string> state_names() const = 0;

  virtual std::vector<std::string> parameter_names() const = 0;
  // The values the system was built with: where a run starts unless it is told otherwise.
  virtual ParameterValues default_parameters() const = 0;
  // A named parameter's value in `p`, and `p` with that parameter set.
  virtual double parameter(const ParameterValues& p, int index) const = 0;
  virtual void set_parameter(ParameterValues& p, int index, double value) const = 0;
  ParameterValues with_parameter(ParameterValues p, int index, double value) const {
    set_parameter(p, index, value);
    return p;
  }
  // Index of a named parameter; throws std::invalid_argument naming the known ones.
  int parameter_index(std::string_view name) const;
  int parameter_count() const { return static_cast<int>(parameter_names().size()); }
  // Size of a ParameterValues of this system (default_parameters().size()).
  int parameter_values_size() const { return static_cast<int>(default_parameters().size()); }

  // The raw calls take `p` as ParameterValues::data().
  virtual void rhs(double t, const double* z, const double* p, double* dz) const = 0;

  // False when f has no derivatives (a discontinuous model): flows then refuse sensitivities.
  virtual bool differentiable() const { return true; }
  // df/dz, n x n.
  virtual void jacobian(double t, const double* z, const double* p, Eigen::MatrixXd& jac) const = 0;
  // f(z + s v)'s Taylor coefficients in s up to `order` (at most kMaxTaylorOrder), for a complex
  // direction v: out[k * n + i] = (D^k f(z)(v, ..., v))_i / k!. The normal-form coefficients of
  // equilibria are made of these (continuation/multilinear_forms.hpp). False where the system
  // cannot: then continuation differences f_x, up to f's third derivative only.
  static constexpr int kMaxTaylorOrder = 5;
  virtual bool taylor_coefficients(double /*t*/, const double* /*z*/, const double* /*p*/,
                                   const std::complex<double>* /*v*/, int /*order*/,
                                   std::complex<double>* /*out*/) const {
    return false;
  }
  // out[j] = J * S[j] for j < columns. The last parameters.size() columns are parameter
  // columns: column columns - parameters.size() + k also gets df/dp for parameters[k] (the
  // forward-sensitivity right-hand side of a parameter).
  virtual void variational_rhs(double t, const double* z, const double* p, int columns,
                               const double* const* S, double* const* out,
                               std::span<const int> parameters) const = 0;
  // f into dz and the variational right-hand side above into out, in one call: what an augmented
  // system's right-hand side needs at every step. This default makes the two calls;
  // AutoDiffSystem reads f off the values of the dual numbers that give J * S (one model
  // evaluation a step fewer: on the anti-phase k-branch, where it is a third of the cost of a
  // step of the orbit with its across block, the fast preset's branch took 0.26 s instead of
  // 0.30 s, bench section (f)).
  virtual void rhs_and_variational(double t, const double* z, const double* p, double* dz,
                                   int columns, const double* const* S, double* const* out,
                                   std::span<const int> parameters) const {
    rhs(t, z, p, dz);
    if (columns > 0) variational_rhs(t, z, p, columns, S, out, parameters);
  }
  // Structurally nonzero entries of df/dz as (row, column) pairs, for sparse linear solvers;
  // empty means dense.
  virtual std::vector<std::pair<int, int>> jacobian_pattern() const { return {}; }
  // df/dz = S + U W^T with S sparse and U W^T of small rank (see LowRankJacobian), for linear
  // solvers that exploit it. low_rank_structure() gives S's pattern and the rank, values zero;
  // nullopt when the system does not provide the form. low_rank_jacobian() fills the values of
  // a structure obtained from low_rank_structure() at (t, z, p) and returns true; false when not
  // provided. Between switching surfaces (switching_functions) it is the Jacobian of the piece
  // that z lies in.
  virtual std::optional<LowRankJacobian> low_rank_structure() const { return std::nullopt; }
  virtual bool low_rank_jacobian(double /*t*/, const double* /*z*/, const double* /*p*/,
                                 LowRankJacobian& /*out*/) const {
    return false;
  }
  // df/dp for one named parameter.
  virtual void parameter_derivative(double t, const double* z, const double* p, int parameter,
                                    double* dfdp) const = 0;

  // Does f depend on t? Autonomous systems have a trivial Floquet multiplier.
  virtual bool autonomous() const { return true; }
  // The period of the forcing at parameter values p, for a periodically forced system that
  // declares it (an equation case file's forcing_period); 0: not declared (then whoever computes
  // its orbits gives the period). Its orbits have this period; no shift in time maps one onto
  // another, so they have no trivial multiplier.
  virtual double forcing_period(const double* /*p*/) const { return 0.0; }

  // States that are angles (indices, increasing): a motion on which one of them gains a multiple
  // of 2 pi over a period (a pendulum that rotates) is periodic all the same (the shooting
  // residual subtracts the gain; see ShootingProblem). Empty: none.
  virtual std::vector<int> angle_states() const { return {}; }

  // Steep zones at parameter values p (a zone's width may depend on them).
  virtual std::vector<SteepZone> steep_zones(const double* /*p*/) const { return {}; }

  // Surfaces g(z) = 0 across which f jumps: a flow stops at each and restarts from there.
  virtual int switching_count() const { return 0; }
  virtual void switching_functions(double /*t*/, const double* /*z*/, const double* /*p*/,
                                   double* /*g*/) const {}
  // Surface i for messages ("th1 = the"); by default "switching surface i".
  virtual std::string switching_name(int i) const {
    return "switching surface " + std::to_string(i);
  }

  // The system restricted to an invariant subspace, in the subspace's representative coordinates
  // (InvariantSubspace::coordinates), with the same parameters, where the model can evaluate it
  // for less than the whole state costs (identical metronomes that move together: one evaluation
  // for all of them); nullptr otherwise (restrict_system then uses the generic restriction).
  // Valid at parameter values that keep the subspace invariant: the caller checks them.
  virtual std::unique_ptr<OdeSystem> restricted(const InvariantSubspace& /*subspace*/) const {
    return nullptr;
  }

  // Convenience wrappers on Eigen vectors.
  Eigen::VectorXd rhs(double t, const Eigen::VectorXd& z, const ParameterValues& p) const;
  Eigen::MatrixXd jacobian(double t, const Eigen::VectorXd& z, const ParameterValues& p) const;
  // Throws std::invalid_argument unless p has this system's size and finite entries.
  void check_parameters(const ParameterValues& p) const;
};

}  // namespace sympathy
