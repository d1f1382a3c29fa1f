// Small systems with exactly known answers, for testing the engine.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "core/autodiff_system.hpp"

namespace sympathy::testing {

// z' = A z with a constant matrix; solution expm(A t) z0.
class LinearSystem final : public AutoDiffSystem<LinearSystem> {
 public:
  explicit LinearSystem(Eigen::MatrixXd a) : a_(std::move(a)) {
    set_parameter_layout({{"scale", {0}}}, {1.0});
  }
  int dimension() const override { return static_cast<int>(a_.rows()); }
  std::vector<std::string> state_names() const override {
    std::vector<std::string> n;
    for (int i = 0; i < dimension(); ++i)
      n.push_back(std::string("z").append(std::to_string(i + 1)));
    return n;
  }
  // z' = scale * A z
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    for (int i = 0; i < dimension(); ++i) {
      T sum(0.0);
      for (int j = 0; j < dimension(); ++j) sum += a_(i, j) * z[j];
      dz[i] = p[0] * sum;
    }
  }

 private:
  Eigen::MatrixXd a_;
};

// z' = -a z: z(t) = z0 exp(-a t), dz/da = -t z0 exp(-a t).
class Decay final : public AutoDiffSystem<Decay> {
 public:
  explicit Decay(double a) { set_parameter_layout({{"a", {0}}}, {a}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"z"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = -p[0] * z[0];
  }
};

// z' = z^2: blows up at t = 1/z0.
class BlowUp final : public AutoDiffSystem<BlowUp> {
 public:
  BlowUp() { set_parameter_layout({}, {}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"z"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    dz[0] = z[0] * z[0];
  }
};

// u' = -1 and q' = exp(-(u/w)^2) / (w sqrt(pi)): a pulse of unit area, width w, as u crosses 0.
// From u = 1 to u = -1, q gains erf(1/w) = 1 to machine precision. Error control alone steps
// over the pulse; the flow must resolve it through the steep zone on u.
class Pulse final : public AutoDiffSystem<Pulse> {
 public:
  explicit Pulse(double width) : width_(width) { set_parameter_layout({}, {}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"u", "q"}; }
  std::vector<SteepZone> steep_zones() const override { return {{0, width_, 1.0}}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    using std::exp;
    const T s = z[0] / width_;
    dz[0] = T(-1.0);
    dz[1] = exp(-s * s) / (width_ * std::sqrt(M_PI));
  }

 private:
  double width_;
};

// The Hopf normal form x' = -y + x(1 - r^2), y' = x + y(1 - r^2): the unit circle is a limit
// cycle of period 2 pi with radial multiplier exp(-4 pi). With `transverse`, a third state
// w' = (-a + b x) w whose multiplier on the cycle (x = cos t) is exp(-2 pi a) exactly.
class HopfCycle final : public AutoDiffSystem<HopfCycle> {
 public:
  explicit HopfCycle(bool transverse = false, double a = 0.5, double b = 0.7)
      : transverse_(transverse) {
    set_parameter_layout({{"a", {0}}, {"b", {1}}}, {a, b});
  }
  int dimension() const override { return transverse_ ? 3 : 2; }
  std::vector<std::string> state_names() const override {
    if (transverse_) return {"x", "y", "w"};
    return {"x", "y"};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T g = 1.0 - (z[0] * z[0] + z[1] * z[1]);
    dz[0] = -z[1] + z[0] * g;
    dz[1] = z[0] + z[1] * g;
    if (transverse_) dz[2] = (-p[0] + p[1] * z[0]) * z[2];
  }

 private:
  bool transverse_;
};

// Two uncoupled Hopf oscillators of the same frequency: every phase difference gives a periodic
// orbit (a one-parameter family), with multipliers 1, 1, exp(-4 pi), exp(-4 pi).
class TwoHopf final : public AutoDiffSystem<TwoHopf> {
 public:
  TwoHopf() { set_parameter_layout({}, {}); }
  int dimension() const override { return 4; }
  std::vector<std::string> state_names() const override { return {"x1", "y1", "x2", "y2"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    for (int k = 0; k < 4; k += 2) {
      const T g = 1.0 - (z[k] * z[k] + z[k + 1] * z[k + 1]);
      dz[k] = -z[k + 1] + z[k] * g;
      dz[k + 1] = z[k] + z[k + 1] * g;
    }
  }
};

// z' = A(t) z with A(t) = [0 1; -10 cos t, -24 - 10 sin t], period 2 pi. In second-order form
// x'' + (24 + 10 sin t) x' + 10 cos t x = d/dt (x' + (24 + 10 sin t) x) = 0, so the Floquet
// exponents are exactly 0 and -24 (multipliers 1 and exp(-48 pi) = 2e-66).
class ForcedFloquet final : public AutoDiffSystem<ForcedFloquet> {
 public:
  ForcedFloquet() { set_parameter_layout({}, {}); }
  int dimension() const override { return 2; }
  bool autonomous() const override { return false; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double t, const T* z, const P*, T* dz) const {
    dz[0] = z[1];
    dz[1] = -10.0 * std::cos(t) * z[0] - (24.0 + 10.0 * std::sin(t)) * z[1];
  }
};

}  // namespace sympathy::testing
