// The equation case files of cases/examples written by hand in C++, with the files' parameter
// values as defaults: what bench section (h) times the generated systems against, and what the
// tests check equilibria, Hopf points and families on (AUTO's demos lrz and abc).
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/autodiff_system.hpp"

namespace sympathy::bench {

// cases/examples/hopf.toml by hand.
class HandHopf final : public AutoDiffSystem<HandHopf> {
 public:
  explicit HandHopf(const Eigen::VectorXd& p = Eigen::Vector2d(0.25, 1.0)) {
    set_parameter_layout({{"mu", {0}}, {"w", {1}}}, {p[0], p[1]});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    dz[0] = p[0] * z[0] - p[1] * z[1] - z[0] * r2;
    dz[1] = p[1] * z[0] + p[0] * z[1] - z[1] * r2;
  }
};

// cases/examples/lrz.toml by hand.
class HandLorenz final : public AutoDiffSystem<HandLorenz> {
 public:
  explicit HandLorenz(const Eigen::VectorXd& p = Eigen::Vector3d(28.0, 10.0, 8.0 / 3.0)) {
    set_parameter_layout({{"rho", {0}}, {"sigma", {1}}, {"beta", {2}}}, {p[0], p[1], p[2]});
  }
  int dimension() const override { return 3; }
  std::vector<std::string> state_names() const override { return {"x", "y", "z"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = p[1] * (z[1] - z[0]);
    dz[1] = p[0] * z[0] - z[1] - z[0] * z[2];
    dz[2] = z[0] * z[1] - p[2] * z[2];
  }
};

// cases/examples/abc.toml by hand.
class HandAbc final : public AutoDiffSystem<HandAbc> {
 public:
  explicit HandAbc(
      const Eigen::VectorXd& p = (Eigen::VectorXd(5) << 0.25, 1.0, 1.55, 8.0, 0.04).finished()) {
    set_parameter_layout({{"p1", {0}}, {"p2", {1}}, {"p3", {2}}, {"p4", {3}}, {"p5", {4}}},
                         {p[0], p[1], p[2], p[3], p[4]});
  }
  int dimension() const override { return 3; }
  std::vector<std::string> state_names() const override { return {"u1", "u2", "u3"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    using std::exp;
    const T e = exp(z[2]);
    dz[0] = -z[0] + p[0] * (1.0 - z[0]) * e;
    dz[1] = -z[1] + p[0] * e * (1.0 - z[0] - p[4] * z[1]);
    dz[2] = -z[2] - p[2] * z[2] + p[0] * p[3] * e * (1.0 - z[0] + p[1] * p[4] * z[1]);
  }
};

}  // namespace sympathy::bench
