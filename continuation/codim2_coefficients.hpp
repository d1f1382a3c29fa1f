// Normal-form coefficients of codimension-two points of equilibria (Kuznetsov, Elements of
// Applied Bifurcation Theory, 3rd ed., ch. 8; MatCont's nf_BT and nf_CP normalisations), from
// f's second and third derivatives by differences of the exact f_x (jacobian_derivatives.hpp).
// Internal to the continuation layer: the curves of equilibria report them at their BT and CP.
#pragma once

#include <optional>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"

namespace sympathy::detail {

// Bogdanov-Takens: w0' = w1, w1' = a w0^2 + b w0 w1, with A q0 = 0, A q1 = q0, A^T p1 = 0,
// A^T p0 = p1 normalised as MatCont does (<q0, q0> = 1, <q0, q1> = 0, <p0, q0> = <p1, q1> = 1,
// <p0, q1> = <p1, q0> = 0): a = <p1, B(q0, q0)> / 2, b = <p0, B(q0, q0)> + <p1, B(q0, q1)>.
// q0's sign is free and flips both: sign(a b) is what the unfolding depends on; here q0's largest
// component is positive. nullopt where A has no double zero eigenvalue.
struct BogdanovTakensCoefficients {
  double a = 0.0, b = 0.0;
};
std::optional<BogdanovTakensCoefficients> bogdanov_takens_coefficients(const OdeSystem& system,
                                                                       const ParameterValues& p,
                                                                       const Eigen::VectorXd& x);

// Cusp: w' = c w^3 on the centre manifold, c = <p, C(q, q, q) + 3 B(q, h2)> / 6 with h2 the
// bordered solution of A h2 = -B(q, q), <q, h2> = 0, |q| = 1, <p, q> = 1 (MatCont's nf_CP; even
// in q's sign).
std::optional<double> cusp_coefficient(const OdeSystem& system, const ParameterValues& p,
                                       const Eigen::VectorXd& x);

// Zero-Hopf: xi' = b xi^2 + c |zeta|^2 + ..., zeta' = i omega zeta + a xi zeta + ... on the centre
// manifold (Kuznetsov 1999; MatCont's nf_ZH), with A q0 = 0, A q1 = i omega q1, |q0| = |q1| = 1,
// <p0, q0> = <p1, q1> = 1: b = <p0, B(q0, q0)> / 2, c = <p0, B(q1, conj q1)>, a = <p1, B(q0,
// q1)>. Which unfolding applies: s = sign(b c) and theta = Re a / (2 b) (MatCont's), both even in
// q0's sign (b, c and a flip with it). nullopt without a zero eigenvalue and a pair.
struct ZeroHopfCoefficients {
  double b = 0.0, c = 0.0, a = 0.0;  // a: its real part
  double s = 0.0, theta = 0.0;
};
std::optional<ZeroHopfCoefficients> zero_hopf_coefficients(const OdeSystem& system,
                                                           const ParameterValues& p,
                                                           const Eigen::VectorXd& x);

// Double Hopf: the amplitudes of w0' = i omega0 w0 + G2100 w0 |w0|^2 + G1011 w0 |w1|^2 + ... and
// w1' = i omega1 w1 + H1110 w1 |w0|^2 + H0021 w1 |w1|^2 + ... (Kuznetsov 1999; MatCont's nf_HH)
// obey r0' = r0 (p11 r0^2 + p12 r1^2), r1' = r1 (p21 r0^2 + p22 r1^2), p11 = Re G2100, p12 = Re
// G1011, p21 = Re H1110, p22 = Re H0021 (|q| = 1, <p, q> = 1 for each pair); the unfolding by
// sign(p11 p22), theta = p12 / p22 and delta = p21 / p11. Pair 0 is the one at +-i omega0 (the
// Hopf curve's own), pair 1 the other nearest the imaginary axis.
struct DoubleHopfCoefficients {
  double p11 = 0.0, p12 = 0.0, p21 = 0.0, p22 = 0.0, theta = 0.0, delta = 0.0;
};
std::optional<DoubleHopfCoefficients> double_hopf_coefficients(const OdeSystem& system,
                                                               const ParameterValues& p,
                                                               const Eigen::VectorXd& x,
                                                               double omega0);

// Generalized Hopf: the second Lyapunov coefficient l2 = Re c2 / omega of the Poincare normal
// form z' = i omega z + c1 z |z|^2 + c2 z |z|^4 (Kuznetsov, "Numerical normalization techniques
// for all codim 2 bifurcations of equilibria in ODEs", SIAM J. Numer. Anal. 36, 1999: c2 =
// G32 / 12 at l1 = 0), with A q = i omega q, |q| = 1, <p, q> = 1: in the units of l1 =
// Re c1 / omega (describe_hopf), so that near the point the Hopf family's parameter moves as
// l1 r^2 + l2 r^4 (MatCont prints Re c2 itself, omega l2). Needs f's fourth and fifth
// derivatives: nullopt for a system without Taylor jets, or without a pair +-i omega.
std::optional<double> second_lyapunov_coefficient(const OdeSystem& system, const ParameterValues& p,
                                                  const Eigen::VectorXd& x, double omega);

}  // namespace sympathy::detail
