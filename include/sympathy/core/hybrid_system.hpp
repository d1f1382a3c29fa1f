// A piecewise-smooth (hybrid) system: smooth vector fields in regions of the state space, bounded
// by switching surfaces h_i(t, z, p) = 0 (OdeSystem::switching_functions), with an optional reset
// (jump) z+ = R_i(z-, p) where a surface is crossed.
//
// What a smooth OdeSystem declares holds inside each region: rhs, jacobian, variational_rhs and
// parameter_derivative are those of the region that z lies in. On top, a hybrid system declares
// the same of a region named by its sides, extended smoothly beyond its surfaces (f- and f+ are
// one-sided limits on a surface, which the state alone cannot choose, and an integrator's step
// that ends past a surface must see the field it started in), and what a flow needs to carry
// sensitivities across a crossing (the saltation matrix, core/saltation.hpp): the surface's
// gradient and the reset with its derivatives. A region is named by the sign of every switching
// function in it (`sides`, +1 or -1 each): a relay's two regions are {v > 0} and {v < 0}.
//
// The flow (core/flow.hpp) integrates the field of the region it is in, locates every crossing
// with the integrator's root finding, restarts the integration there in the new region (no step
// straddles a discontinuity: a step that did, with the field read off the state, put a noise of
// 1e-9 into the metronome's shooting residual at rtol 1e-12, and Newton converged linearly) and
// maps the sensitivity columns by the saltation matrix; so the transition matrix and the parameter
// sensitivities, the monodromy of a periodic orbit and its multipliers, are those of the hybrid
// flow, exactly as for a smooth one. Systems that are not HybridSystems keep switching surfaces
// for plain integration only (the flow refuses sensitivities across them).
#pragma once

#include <span>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"

namespace sympathy {

class HybridSystem : public OdeSystem {
 public:
  // Which crossings of surface i are events: +1 only where h_i increases, -1 only where it
  // decreases, 0 both ways. A crossing the other way is no event at all (no restart, no reset):
  // declare a direction only where f does not jump the other way (an impact surface, reached only
  // from one side).
  virtual int crossing_direction(int /*surface*/) const { return 0; }

  // f of the region on `sides` (switching_count() entries, +1 or -1: the sign of each h_i there),
  // at z, which may lie on a surface of that region or just beyond it: the one-sided limits f-
  // and f+ of a crossing.
  virtual void rhs_on_sides(double t, const double* z, const double* p, const int* sides,
                            double* dz) const = 0;
  // The region's derivatives, as OdeSystem's jacobian, variational_rhs and rhs_and_variational
  // (AutoDiffHybridSystem writes them from one templated field).
  virtual void jacobian_on_sides(double t, const double* z, const double* p, const int* sides,
                                 Eigen::MatrixXd& jac) const = 0;
  virtual void variational_rhs_on_sides(double t, const double* z, const double* p,
                                        const int* sides, int columns, const double* const* S,
                                        double* const* out,
                                        std::span<const int> parameters) const = 0;
  virtual void rhs_and_variational_on_sides(double t, const double* z, const double* p,
                                            const int* sides, double* dz, int columns,
                                            const double* const* S, double* const* out,
                                            std::span<const int> parameters) const = 0;

  // The gradient of h_i: h_z (n entries) and dh_i/dt (returned; 0 for a surface fixed in time).
  virtual double switching_gradient(double t, const double* z, const double* p, int surface,
                                    double* h_z) const = 0;
  // dh_i/dp for one named parameter (a surface that moves with a parameter moves the event time).
  virtual double switching_parameter_derivative(double /*t*/, const double* /*z*/,
                                                const double* /*p*/, int /*surface*/,
                                                int /*parameter*/) const {
    return 0.0;
  }

  // Whether crossing surface i resets the state; without one the state is continuous there.
  virtual bool has_reset(int /*surface*/) const { return false; }
  // z+ = R_i(z-, p), its Jacobian R_z (n x n) and dR/dp for one named parameter (n entries); the
  // reset does not depend on t. Called only where has_reset(i).
  virtual void reset(double /*t*/, const double* z, const double* /*p*/, int /*surface*/,
                     double* z_plus) const {
    for (int i = 0; i < dimension(); ++i) z_plus[i] = z[i];
  }
  virtual void reset_jacobian(double /*t*/, const double* /*z*/, const double* /*p*/,
                              int /*surface*/, Eigen::MatrixXd& r_z) const {
    r_z = Eigen::MatrixXd::Identity(dimension(), dimension());
  }
  virtual void reset_parameter_derivative(double /*t*/, const double* /*z*/, const double* /*p*/,
                                          int /*surface*/, int /*parameter*/, double* r_p) const {
    for (int i = 0; i < dimension(); ++i) r_p[i] = 0.0;
  }
};

// Whether a flow of `system` carries sensitivities: it has no switching surfaces, or it is a
// HybridSystem (a restriction of one to a subspace that is not one itself does not).
inline bool carries_sensitivities(const OdeSystem& system) {
  return system.switching_count() == 0 || dynamic_cast<const HybridSystem*>(&system) != nullptr;
}

}  // namespace sympathy
