// Periodic orbits at Hopf points: the Hopf point where a family of orbits ends (its orbits
// shrinking into an equilibrium), and the small orbit a family born at a Hopf point starts from.
//
// At a Hopf point (x_H, p_H) with eigenvalues +-i omega and eigenvector q, the orbits born there
// are x_H + eps (Re q cos(omega t) - Im q sin(omega t)) + O(eps^2) at p - p_H = O(eps^2), period
// 2 pi / omega + O(eps^2). A fixed parameter does not determine the small orbit (at p_H itself
// there is none, and the shooting Jacobian has a double multiplier 1 there), a fixed amplitude
// does: Newton on the shooting equations, the phase condition (a section through
// x_H + eps Re q across Im q, the direction of the motion there) and <Re q, z0 - x_H> =
// eps |Re q|^2, the parameter free. Its solution is an ordinary orbit of the family, which
// continuation then follows (AUTO's IPS = 2 start from a Hopf label does the same with
// collocation).
#pragma once

#include <optional>
#include <string>

#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/equilibrium.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

struct HopfStartOptions {
  // Of the first orbit along Re q, in state units; 0: 0.02 max(1, |x_H|_inf). Its multiplier
  // nearest 1 (other than the trivial one) moves away from 1 like eps^2: too small an eps leaves
  // it within the rank tolerance of 1 and the orbit is taken for a member of a continuum.
  double amplitude = 0.0;
  int max_iterations = 15;
  OptionCheck validate() const;
};

// The Hopf point of the equilibrium near `guess` (at values `p`) whose eigenvalues have a pair
// near i * omega_guess (within 20%): the equilibrium is followed in `parameter` (Newton at each
// value) while secant steps drive the pair's real part to zero, from `p`'s value and that value
// plus `step`. nullopt, with the reason in `why`, where there is no equilibrium near, no such
// pair, or the secant does not converge in 40 steps.
std::optional<HopfPoint> hopf_point_near(const OdeSystem& system, int parameter,
                                         const ParameterValues& p, const Eigen::VectorXd& guess,
                                         double omega_guess, double step, std::string& why);

// The family born at `hopf` to second order in its amplitude, from the normal form: the orbit of
// amplitude eps along Re q (x - x_H = eps (Re q cos(omega t) - Im q sin(omega t)), |q| = 1) lies
// at p - p_H = offset eps^2 and turns at the angular frequency omega + frequency eps^2 (each
// + O(eps^3)). On Kuznetsov's w = (eps / 2) e^(i Omega t), w' = (mu(p) + i omega(p)) w +
// c1 |w|^2 w: offset = -Re c1 / (4 mu'), frequency = (Im c1 - omega' Re c1 / mu') / 4, with
// l1 = Re c1 / omega. The offset's sign says on which side of p_H the family lies; Newton on the
// first orbit starts there, at the period 2 pi / (omega + frequency eps^2). mu' and omega' (the
// pair's derivatives in p) by central differences of the equilibrium's pair (step 1e-6
// relative). nullopt where l1 or mu' is unknown or zero; frequency 0 where c1 is unknown.
struct HopfExpansion {
  double offset = 0.0;     // (p - p_H) / eps^2
  double frequency = 0.0;  // (Omega - omega) / eps^2
};
std::optional<HopfExpansion> hopf_expansion(const OdeSystem& system, int parameter,
                                            const HopfPoint& hopf);

// The small orbit of the family born at `hopf` (hopf.values, the continued `parameter`), as
// above; where Newton fails at the amplitude asked for, retried at a quarter and a sixteenth of
// it. Throws std::runtime_error naming what failed at each.
PeriodicOrbit orbit_from_hopf(const OdeSystem& system, int parameter, const HopfPoint& hopf,
                              const OrbitOptions& options, const HopfStartOptions& start = {});

// The family of periodic orbits born at `hopf`: its small orbit (orbit_from_hopf), continued in
// `parameter` within the options' bounds, away from the Hopf point: the way its amplitude grows
// (the secant to the orbit of twice the amplitude; where that one fails, the side of the Hopf
// point the small orbit lies on); the branch's origin names the Hopf point. Throws
// std::runtime_error where no orbit near the Hopf point converges.
Branch continue_from_hopf(const OdeSystem& system, int parameter, const HopfPoint& hopf,
                          const ContinuationOptions& options,
                          const ContinuationCallbacks& callbacks = {},
                          const HopfStartOptions& start = {});

}  // namespace sympathy
