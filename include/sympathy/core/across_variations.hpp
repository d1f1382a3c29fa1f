// An orbit of a symmetric subspace with its variational equations across the subspace, as one
// plain system: the block of the monodromy that breaks the symmetry, at the cost of that block.
//
// Where a reflection g keeps f (f(g z) = g f(z); InvariantSubspace::reflection) and an orbit lies
// in g's fixed space V, the Jacobian along the orbit commutes with g and maps V and its orthogonal
// complement W (g's -1 eigenspace) each into itself: in the basis [coordinates of V, C] (C an
// orthonormal basis of W, Reflection::breaking_basis) the variational equations are two blocks,
// the one inside V (the restricted system's, ReducedSystem) and A(t) = C^T J(z(t)) C across it.
// This system's state is w = (y, U): y the coordinates of V (z = P y), U the a x a matrix
// (column-major) of the across block's solution, with
//   y' = R f(P y),    U' = C^T J(P y) C U,
// so a plain integration from (y0, I) over a period gives the orbit and the across block of its
// monodromy: on the row setup's anti-phase orbit 2 + 16 entries in the flow's vector instead of
// 6 + 6 x 6 (+ 6 for a parameter column), and one dual-number evaluation with 4 directions a step
// instead of 7. U is in the error test, as the flows keep sensitivities (flow.hpp).
//
// With `inside_block` the state also carries V's own block Y (r x r, column-major, Y' = R J P Y,
// the restricted system's variational equations) and, for a parameter index >= 0, its parameter
// column s (s' = R (J P s + df/dp); df/dp lies in V where f keeps g), between y and U:
// w = (y, Y, s, U). One plain run from (y0, I, 0, I) then gives the whole monodromy of an orbit
// that moves with the parameter, P Y R on V plus C U C^T on W, and dz/dp = P s: on the row
// setup's in-phase orbit 4 + 16 + 4 + 4 = 28 entries instead of 6 + 36 + 6 = 48, with the same
// one dual-number evaluation a step (4 + 1 + 2 directions instead of 6 + 1).
//
// The Jacobian handed to an implicit method is the block diagonal of df/dy (for y, each column of
// Y and s) and I (x) A(t): the block equations' dependence on y (through J and df/dp) is left
// out, a modified Newton iteration (exact for y; the blocks' equations are linear). `state_names`
// name y by V's representative components, Y, s and U by their entries.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/invariant_subspace.hpp"
#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/reduced_system.hpp"
#include "sympathy/core/system_over.hpp"

namespace sympathy {

class AcrossVariations final : public SystemOver {
 public:
  // `system` must outlive this; `subspace` must have a reflection (throws std::invalid_argument
  // otherwise), and a parameter column needs `inside_block`. The caller checks that f keeps the
  // reflection at the parameter values it uses.
  AcrossVariations(const OdeSystem& system, const InvariantSubspace& subspace,
                   bool inside_block = false, int parameter = -1);

  int inside() const { return coordinates_.size(); }                 // r: V's coordinates
  int across() const { return static_cast<int>(breaking_.cols()); }  // a: W's dimension
  int column_parameter() const { return parameter_; }                // of the column s; -1: none
  const InvariantSubspace::Coordinates& coordinates() const { return coordinates_; }
  const Eigen::MatrixXd& breaking_basis() const { return breaking_; }  // C, n x a
  // The state (y0, I, 0, I) for an orbit through z0 (in V), and the blocks read from a state:
  // U (a x a), Y (r x r; empty without inside_block) and s (r; empty without a parameter).
  Eigen::VectorXd start(const Eigen::VectorXd& z0) const;
  Eigen::MatrixXd block(const Eigen::VectorXd& w) const;
  Eigen::MatrixXd inside_block(const Eigen::VectorXd& w) const;
  Eigen::VectorXd parameter_column(const Eigen::VectorXd& w) const;

  using OdeSystem::jacobian;
  using OdeSystem::rhs;
  int dimension() const override { return across_offset() + across() * across(); }
  std::vector<std::string> state_names() const override;
  void rhs(double t, const double* w, const double* p, double* dw) const override;
  void jacobian(double t, const double* w, const double* p, Eigen::MatrixXd& jac) const override;
  // J * S with the Jacobian above (for completeness; a flow of this system needs no
  // sensitivities). Parameter columns are refused (std::invalid_argument): the system's own
  // parameter column is part of its state.
  void variational_rhs(double t, const double* w, const double* p, int columns,
                       const double* const* S, double* const* out,
                       std::span<const int> parameters) const override;
  // Refused (std::invalid_argument): the block carries no parameter sensitivities.
  void parameter_derivative(double t, const double* w, const double* p, int parameter,
                            double* dfdp) const override;
  std::vector<SteepZone> steep_zones(const double* p) const override;  // y's, as ReducedSystem's
  void switching_functions(double t, const double* w, const double* p, double* g) const override;

 private:
  Eigen::VectorXd embed(const double* w) const;
  int column_offset() const { return inside() * (1 + (inside_block_ ? inside() : 0)); }     // s
  int across_offset() const { return column_offset() + (parameter_ >= 0 ? inside() : 0); }  // U
  struct Scratch {  // rhs's temporaries
    Eigen::VectorXd z, dz;
    Eigen::MatrixXd in, out;
    std::vector<const double*> in_columns;
    std::vector<double*> out_columns;
  };

  ReducedSystem reduced_;  // y's equations, zones and names
  const InvariantSubspace::Coordinates& coordinates_;
  Eigen::MatrixXd breaking_;
  // C's nonzero entries (C(state, column) = value), the only terms of C U and C^T (J C U): one or
  // two per column (6 of 24 for the row setup's anti-phase orbit).
  struct Entry {
    int state, column;
    double value;
  };
  std::vector<Entry> breaking_entries_;
  bool inside_block_;
  int parameter_;
};

}  // namespace sympathy
