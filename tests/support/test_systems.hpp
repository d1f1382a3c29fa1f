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

}  // namespace sympathy::testing
