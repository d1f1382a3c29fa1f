// A system restricted to an invariant subspace, in the subspace's representative coordinates.
//
// On a subspace V that f keeps (z in V gives f(z) in V), z = P y for the coordinates y of V
// (InvariantSubspace::coordinates: each a representative component, the others equal to it up to
// sign, or zero), and y' = R f(P y), where R reads the representatives. The restriction's flow
// is the flow inside V, and its variational equations are those of perturbations inside V: an
// orbit of the subspace and its multipliers on V cost what the small system costs to integrate.
// The generic restriction here evaluates f on the whole state, O(n) a call; a model may offer a
// cheaper one (OdeSystem::restricted), which restrict_system prefers.
#pragma once

#include <memory>

#include "sympathy/core/invariant_subspace.hpp"
#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/system_over.hpp"

namespace sympathy {

class ReducedSystem final : public SystemOver {
 public:
  // `system` must outlive this.
  ReducedSystem(const OdeSystem& system, const InvariantSubspace& subspace);

  const InvariantSubspace::Coordinates& coordinates() const { return coordinates_; }
  using OdeSystem::jacobian;  // the Eigen wrappers, which the overrides below would hide
  using OdeSystem::rhs;

  int dimension() const override { return coordinates_.size(); }
  std::vector<std::string> state_names() const override;
  void rhs(double t, const double* y, const double* p, double* dy) const override;
  bool differentiable() const override { return system_.differentiable(); }
  void jacobian(double t, const double* y, const double* p, Eigen::MatrixXd& jac) const override;
  void variational_rhs(double t, const double* y, const double* p, int columns,
                       const double* const* S, double* const* out,
                       std::span<const int> parameters) const override;
  void rhs_and_variational(double t, const double* y, const double* p, double* dy, int columns,
                           const double* const* S, double* const* out,
                           std::span<const int> parameters) const override;
  void parameter_derivative(double t, const double* y, const double* p, int parameter,
                            double* dfdp) const override;
  // The whole system's zones on components that are coordinates here (a zero component has
  // none to resolve).
  std::vector<SteepZone> steep_zones(const double* p) const override;
  void switching_functions(double t, const double* y, const double* p, double* g) const override;

 private:
  Eigen::VectorXd embed(const double* y) const;
  void variational(double t, const double* y, const double* p, int columns, const double* const* S,
                   double* const* out, std::span<const int> parameters, double* dy) const;

  InvariantSubspace::Coordinates coordinates_;
};

// The system restricted to `subspace`: the model's own restriction where it has one, the generic
// one otherwise. The result may refer to `system`, which must outlive it.
std::unique_ptr<OdeSystem> restrict_system(const OdeSystem& system,
                                           const InvariantSubspace& subspace);

}  // namespace sympathy
