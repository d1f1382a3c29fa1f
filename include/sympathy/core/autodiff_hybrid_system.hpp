// A HybridSystem whose fields and derivatives come from one templated right-hand side per region.
//
// The derived class writes, beside AutoDiffSystem's evaluate,
//   template <class T, class P>
//   void evaluate_on_sides(double t, const T* z, const P* raw, T* dz, const int* sides) const;
// the field of the region named by `sides` (HybridSystem), extended smoothly beyond its surfaces;
// the region's rhs, Jacobian and variational columns follow from it as AutoDiffSystem's do from
// evaluate. The surfaces, their gradients and any resets it declares by hand.
#pragma once

#include "sympathy/core/autodiff_system.hpp"
#include "sympathy/core/hybrid_system.hpp"

namespace sympathy {

template <class Derived>
class AutoDiffHybridSystem : public AutoDiffSystem<Derived, HybridSystem> {
  using Base = AutoDiffSystem<Derived, HybridSystem>;

 public:
  void rhs_on_sides(double t, const double* z, const double* p, const int* sides,
                    double* dz) const override {
    derived().evaluate_on_sides(t, z, p, dz, sides);
  }
  void jacobian_on_sides(double t, const double* z, const double* p, const int* sides,
                         Eigen::MatrixXd& jac) const override {
    this->jacobian_of(region(sides), t, z, p, jac);
  }
  void variational_rhs_on_sides(double t, const double* z, const double* p, const int* sides,
                                int columns, const double* const* S, double* const* out,
                                std::span<const int> parameters) const override {
    this->variational_of(region(sides), t, z, p, columns, S, out, parameters, nullptr);
  }
  void rhs_and_variational_on_sides(double t, const double* z, const double* p, const int* sides,
                                    double* dz, int columns, const double* const* S,
                                    double* const* out,
                                    std::span<const int> parameters) const override {
    // f from the state columns' dual numbers where there are any, as AutoDiffSystem does.
    if (columns - static_cast<int>(parameters.size()) <= 0) rhs_on_sides(t, z, p, sides, dz);
    this->variational_of(region(sides), t, z, p, columns, S, out, parameters,
                         columns - static_cast<int>(parameters.size()) > 0 ? dz : nullptr);
  }

 protected:
  AutoDiffHybridSystem() = default;

 private:
  const Derived& derived() const { return static_cast<const Derived&>(*this); }
  auto region(const int* sides) const {
    return [this, sides](double t, const auto* z, const auto* p, auto* dz) {
      derived().evaluate_on_sides(t, z, p, dz, sides);
    };
  }
};

}  // namespace sympathy
