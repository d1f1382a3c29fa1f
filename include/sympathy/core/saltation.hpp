// Sensitivities across a crossing of a switching surface: the saltation matrix.
//
// At a crossing of h(t, z, p) = 0 at time tau, with f- the vector field before it and f+ the one
// after it at the reset state z+ = R(z-, p), a perturbation dz- of the state just before the
// surface moves the crossing time by dtau = -(h_z dz- + h_p dp) / (h_z f- + h_t), so that just
// after it
//     dz+ = S dz- + (R_p + (f+ - R_z f-) h_p / (h_z f- + h_t)) dp,
//     S   = R_z + (f+ - R_z f-) h_z / (h_z f- + h_t)                        (the saltation matrix)
// (Aizerman and Gantmacher 1958; Leine and Nijmeijer 2004, ch. 7; di Bernardo et al. 2008,
// ch. 2). Without a reset R_z = I and R_p = 0, and S = I where f is continuous: then only the
// location of the event matters.
//
// Several surfaces crossed at one instant (two identical pendula turning together) are crossed
// one after the other; a perturbation chooses the order in which they are hit, so the flow is
// differentiable there only if both orders give the same map: the saltation matrices commute
// (as where each surface and each jump concern other components: uncoupled relays, or the
// escapement's torque that jumps one pendulum's velocity where only that pendulum's surfaces
// see it). Where they do not, the return map has a corner and no derivative: cross_surfaces
// reports it (NonsmoothFlowError) rather than return one of the two one-sided derivatives.
#pragma once

#include <span>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/errors.hpp"
#include "sympathy/core/hybrid_system.hpp"

namespace sympathy {

// The flow has no derivative where the caller asked for one, or no single continuation at all:
// a grazing crossing (h_z f- + h_t = 0, the orbit touches the surface), simultaneous crossings
// whose saltation matrices do not commute (a corner of the flow map), sliding (both fields push
// towards a surface), a start on a surface that both fields push away from (two solutions), or
// chattering (crossings accumulating at a finite time). time(): where it happens.
class NonsmoothFlowError : public IntegrationError {
 public:
  using IntegrationError::IntegrationError;
};

// S = R_z + (f+ - R_z f-) h_z / (h_z f- + h_t) for one crossing.
Eigen::MatrixXd saltation_matrix(const Eigen::VectorXd& f_minus, const Eigen::VectorXd& f_plus,
                                 const Eigen::RowVectorXd& h_z, double h_t,
                                 const Eigen::MatrixXd& r_z);
// R_p + (f+ - R_z f-) h_p / (h_z f- + h_t): the jump of a parameter's sensitivity column beyond
// S times it.
Eigen::VectorXd parameter_jump(const Eigen::VectorXd& f_minus, const Eigen::VectorXd& f_plus,
                               const Eigen::RowVectorXd& h_z, double h_t,
                               const Eigen::MatrixXd& r_z, double h_p, const Eigen::VectorXd& r_p);

// What the crossings of one instant do: the state and sides after them, and the affine map of the
// sensitivity columns, X+ = saltation X- for state columns and x_p+ = saltation x_p- +
// parameter_jump.col(k) for the k-th of the asked parameters.
struct HybridEvent {
  Eigen::VectorXd state;
  std::vector<int> sides;
  Eigen::MatrixXd saltation;       // n x n (empty unless derivatives were asked)
  Eigen::MatrixXd parameter_jump;  // n x parameters.size()
  // For two or more surfaces: the largest entry of the difference between the maps of the
  // ascending and the descending order of the surfaces, relative to the largest entry of either
  // (0 for one surface; the rounding of the formulas, ~1e-16, where they commute).
  double order_difference = 0.0;
};

// Saltation matrices of simultaneous crossings that differ by more than this (relative, entry by
// entry) in the two orders are a corner. A tolerance, not an accuracy: commuting matrices agree
// to rounding (the test's two relays: 0), non-commuting ones differ at order one.
constexpr double kCornerTolerance = 1e-8;
// |h_z f- + h_t| below this times |h_z| |f-| + |h_t| is a grazing crossing.
constexpr double kGrazingTolerance = 1e-10;

// Crosses `surfaces` (indices of switching functions, increasing) at (t, z) on `sides` (the
// region the flow comes from), applying each surface's reset; with `derivatives`, the saltation
// and parameter jumps for `parameters` too, and for two or more surfaces a NonsmoothFlowError
// where the two orders differ by more than kCornerTolerance. A surface without a reset is left
// for the other side (its side flips); after a reset the flow continues on the side that f
// points into at z+ (an impact: back into the region it came from). Throws NonsmoothFlowError
// at a grazing crossing.
HybridEvent cross_surfaces(const HybridSystem& system, double t, const Eigen::VectorXd& z,
                           const ParameterValues& p, const std::vector<int>& sides,
                           std::span<const int> surfaces, std::span<const int> parameters,
                           bool derivatives);

// The side (+1 or -1) of surface `surface` that a flow starting on it (h = 0 at z) enters, the
// other surfaces on `sides`: the side both one-sided fields carry it into (where one is tangent,
// the other's). Where both push towards the surface the solution slides along it: refused by
// name (NonsmoothFlowError). Where both push away from it, two solutions start at z (a pendulum
// at rest inside the escapement's window with its gravity torque below s: torque +s for th' > 0,
// -s for th' < 0): the one that the field at z (`field`, the model's own value on the surface)
// points into is followed, and `two_solutions` says so. A surface with a reset or a declared
// crossing direction is left to `field`.
struct StartSide {
  int side = 1;
  std::string two_solutions;  // empty unless two solutions start at z: which one is followed
};
StartSide side_entered(const HybridSystem& system, double t, const Eigen::VectorXd& z,
                       const ParameterValues& p, std::vector<int> sides, int surface,
                       const Eigen::VectorXd& field);

}  // namespace sympathy
