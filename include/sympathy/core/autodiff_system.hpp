// An OdeSystem whose derivatives come from one templated right-hand side.
//
// The derived class writes
//   template <class T, class P>
//   void evaluate(double t, const T* z, const P* raw, T* dz) const;
// where `raw` are the parameter values of the call (ParameterValues, the model's raw layout), and
// which sets every entry of dz (it is handed the integrator's own vector, not a zeroed one).
// T is double or a dual number; P is double, or the same dual as T when a parameter derivative
// is wanted. Named parameters are directions in raw parameter space: a name maps to the raw
// entries it sets together (e.g. a damping shared by several metronomes), so df/dp for a name is
// the derivative along that direction.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "sympathy/core/dual.hpp"
#include "sympathy/core/jet.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

struct NamedParameter {
  std::string name;
  std::vector<int> raw;  // raw entries set together by this name
  double scale = 1.0;    // raw value = scale * named value (e.g. degrees to radians)
};

// Base: OdeSystem, or an interface derived from it (a HybridSystem, whose extra declarations the
// derived class writes by hand).
template <class Derived, class Base = OdeSystem>
class AutoDiffSystem : public Base {
 public:
  std::vector<std::string> parameter_names() const override {
    std::vector<std::string> names;
    names.reserve(named_.size());
    for (const auto& p : named_) names.push_back(p.name);
    return names;
  }
  ParameterValues default_parameters() const override {
    return Eigen::Map<const Eigen::VectorXd>(raw_.data(), static_cast<Eigen::Index>(raw_.size()));
  }
  double parameter(const ParameterValues& values, int index) const override {
    const auto& p = named_.at(index);
    return values[p.raw.front()] / p.scale;
  }
  void set_parameter(ParameterValues& values, int index, double value) const override {
    const auto& p = named_.at(index);
    for (int r : p.raw) values[r] = p.scale * value;
  }

  void rhs(double t, const double* z, const double* p, double* dz) const override {
    derived().evaluate(t, z, p, dz);
  }
  using Base::rhs;

  void jacobian(double t, const double* z, const double* p, Eigen::MatrixXd& jac) const override {
    jacobian_of(field(), t, z, p, jac);
  }
  using Base::jacobian;

  void variational_rhs(double t, const double* z, const double* p, int columns,
                       const double* const* S, double* const* out,
                       std::span<const int> parameters) const override {
    variational_of(field(), t, z, p, columns, S, out, parameters, nullptr);
  }

  // f read off the values of the dual numbers of the first state columns (the same operations on
  // the same doubles as rhs, rounded differently in places: within 1.6e-16 of its largest entry,
  // tested); without state columns, the two calls.
  void rhs_and_variational(double t, const double* z, const double* p, double* dz, int columns,
                           const double* const* S, double* const* out,
                           std::span<const int> parameters) const override {
    if (columns - static_cast<int>(parameters.size()) <= 0) {
      Base::rhs_and_variational(t, z, p, dz, columns, S, out, parameters);
      return;
    }
    variational_of(field(), t, z, p, columns, S, out, parameters, dz);
  }

  // The right-hand side on jets (core/jet.hpp) seeded with z + s v.
  bool taylor_coefficients(double t, const double* z, const double* p,
                           const std::complex<double>* v, int order,
                           std::complex<double>* out) const override {
    using J = Jet<OdeSystem::kMaxTaylorOrder>;
    if (order < 0 || order > OdeSystem::kMaxTaylorOrder) return false;
    const int n = this->dimension();
    std::vector<J> zj(n), dzj(n);
    for (int i = 0; i < n; ++i) {
      zj[i] = J(z[i]);
      zj[i].c[1] = v[i];
    }
    derived().evaluate(t, zj.data(), p, dzj.data());
    for (int k = 0; k <= order; ++k)
      for (int i = 0; i < n; ++i) out[k * n + i] = dzj[i].c[k];
    return true;
  }

  void parameter_derivative(double t, const double* z, const double* p, int parameter,
                            double* dfdp) const override {
    using D = Dual<1>;
    const int n = this->dimension();
    std::vector<D> zd(z, z + n), dzd(n), pd;
    seed_parameters(p, parameter, pd);
    derived().evaluate(t, zd.data(), pd.data(), dzd.data());
    for (int i = 0; i < n; ++i) dfdp[i] = dzd[i].d[0];
  }

 protected:
  AutoDiffSystem() = default;
  void set_parameter_layout(std::vector<NamedParameter> named, std::vector<double> raw) {
    for (const auto& p : named)
      for (int r : p.raw)
        if (r < 0 || r >= static_cast<int>(raw.size()))
          throw std::logic_error("parameter '" + p.name + "' points outside the raw parameters");
    named_ = std::move(named);
    raw_ = std::move(raw);
  }
  // The named parameters as directions in the raw layout (for derivatives a derived class
  // writes by hand, such as a switching surface's in a parameter).
  const std::vector<NamedParameter>& named_parameters() const { return named_; }

  // The derivatives of a field written once on any number type, eval(t, z, p, dz): the derived
  // class's evaluate (field()), or a hybrid system's field of one region (AutoDiffHybridSystem).
  template <class Eval>
  void jacobian_of(const Eval& eval, double t, const double* z, const double* p,
                   Eigen::MatrixXd& jac) const {
    const int n = this->dimension();
    jac.resize(n, n);
    for (int c0 = 0; c0 < n;) {
      const int width = std::min(n - c0, 8);
      // Seed the unit directions c0 .. c0+width-1.
      auto seed = [&](auto tag) {
        using D = decltype(tag);
        std::vector<D> zd(n), dzd(n);
        for (int i = 0; i < n; ++i) zd[i] = D(z[i]);
        for (int k = 0; k < width; ++k) zd[c0 + k].d[k] = 1.0;
        eval(t, zd.data(), p, dzd.data());
        for (int i = 0; i < n; ++i)
          for (int k = 0; k < width; ++k) jac(i, c0 + k) = dzd[i].d[k];
      };
      dispatch_width(width, seed);
      c0 += width;
    }
  }

  // J * S for the state columns in chunks of up to 8 directions, then J * s + df/dp for each
  // parameter column; with `f`, f too, from the first chunk's values.
  template <class Eval>
  void variational_of(const Eval& eval, double t, const double* z, const double* p, int columns,
                      const double* const* S, double* const* out, std::span<const int> parameters,
                      double* f) const {
    const int n = this->dimension();
    const int state_columns = columns - static_cast<int>(parameters.size());
    for (int c0 = 0; c0 < state_columns;) {
      const int width = std::min(state_columns - c0, 8);
      auto seed = [&](auto tag) {
        using D = decltype(tag);
        // Kept per thread between calls (one system serves several threads): no allocation a
        // step on the augmented flows' hot path.
        thread_local std::vector<D> zd, dzd;
        zd.resize(n);   // every entry set below
        dzd.resize(n);  // every entry set by evaluate, as rhs has it (zeroing: 1.6% of fast)
        for (int i = 0; i < n; ++i) {
          zd[i] = D(z[i]);
          for (int k = 0; k < width; ++k) zd[i].d[k] = S[c0 + k][i];
        }
        eval(t, zd.data(), p, dzd.data());
        if (f && c0 == 0)
          for (int i = 0; i < n; ++i) f[i] = dzd[i].v;
        for (int k = 0; k < width; ++k)
          for (int i = 0; i < n; ++i) out[c0 + k][i] = dzd[i].d[k];
      };
      dispatch_width(width, seed);
      c0 += width;
    }
    for (int k = 0; k < static_cast<int>(parameters.size()); ++k) {
      // J*s + df/dp in one pass: the state seeded with s, the parameter direction seeded too
      // (per-thread buffers, as above: this runs at every step of a flow with a parameter column).
      const int column = state_columns + k;
      using D = Dual<1>;
      thread_local std::vector<D> zd, dzd, pd;
      zd.resize(n);
      dzd.assign(n, D{});
      for (int i = 0; i < n; ++i) {
        zd[i] = D(z[i]);
        zd[i].d[0] = S[column][i];
      }
      seed_parameters(p, parameters[k], pd);
      eval(t, zd.data(), pd.data(), dzd.data());
      for (int i = 0; i < n; ++i) out[column][i] = dzd[i].d[0];
    }
  }

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  // The derived class's evaluate as a callable on any number type.
  auto field() const {
    return [this](double t, const auto* z, const auto* p, auto* dz) {
      derived().evaluate(t, z, p, dz);
    };
  }

  // The raw parameter values as dual numbers, the direction of named parameter `parameter` seeded.
  void seed_parameters(const double* values, int parameter, std::vector<Dual<1>>& pd) const {
    pd.assign(values, values + raw_.size());
    const auto& p = named_.at(parameter);
    for (int r : p.raw) pd[r].d[0] = p.scale;
  }

  // Narrow duals for narrow chunks: a 2-state system should not pay for 8 directions.
  template <class F>
  static void dispatch_width(int width, F& f) {
    if (width <= 2) {
      f(Dual<2>{});
    } else if (width <= 4) {
      f(Dual<4>{});
    } else {
      f(Dual<8>{});
    }
  }

  std::vector<NamedParameter> named_;
  std::vector<double> raw_;  // the values the system was built with (default_parameters)
};

}  // namespace sympathy
