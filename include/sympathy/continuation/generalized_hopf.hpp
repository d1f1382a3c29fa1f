// The fold of cycles born at a generalized Hopf point (GH: l1 = 0 on a Hopf curve of equilibria),
// followed in both parameters: the switch MatCont and BifurcationKit make from GH to a curve of
// LPC (Kuznetsov, Meijer, Govaerts and Sautois, Physica D 237, 2008), here by the normal form
// and the tools that exist, each checked where it works:
//   1. the side: near GH the Hopf family's radius obeys r' = r (mu + omega (l1 r^2 + l2 r^4)), so
//      a fold of cycles exists where l1 l2 < 0, at r^2 = -l1 / (2 l2); the Hopf point is moved
//      along the Hopf curve (the second parameter stepped, the first found by hopf_point_near)
//      until its l1 puts that fold at the amplitude asked for;
//   2. the family born there is continued in the first parameter (continue_from_hopf) from a
//      third of that amplitude until it turns: the fold, located as every LP is;
//   3. that fold's curve in both parameters (continue_curve), both ways: towards GH, where its
//      cycles shrink into the equilibrium, and away.
#pragma once

#include <string>

#include <Eigen/Dense>

#include "sympathy/continuation/bifurcation_curve.hpp"
#include "sympathy/continuation/continuation.hpp"
#include "sympathy/continuation/equilibrium_curve.hpp"
#include "sympathy/continuation/hopf.hpp"

namespace sympathy {

// A located GH point of a Hopf curve of equilibria (its omega^2 the point's kappa) and its second
// Lyapunov coefficient (codim2_coefficients: Re c2 / omega).
struct GeneralizedHopfPoint {
  CodimensionTwoPoint at;
  double l2 = 0.0;
};
struct GeneralizedHopfOptions {
  // The fold's orbits where the family is started, along Re q in state units; 0: 0.1 max(1,
  // |x|_inf). Small enough for the normal form to place the fold, large enough for the family to
  // turn well away from the Hopf point (its parameter offset grows as the amplitude's fourth
  // power).
  double amplitude = 0.0;
  ContinuationOptions family;  // its bounds: the curve's first window
  HopfStartOptions start;      // amplitude 0: a third of the fold's
  CurveOptions curve;
};

struct GeneralizedHopfFold {
  HopfPoint hopf;  // on the Hopf curve, where the family was started
  Branch family;   // in the first parameter, to its first fold
  Bifurcation fold;
  BifurcationCurve curve;
};

// Throws std::invalid_argument for a point without l2 (a system without fifth derivatives) or l2
// = 0, parameters that are not two different ones, options that do not validate;
// std::runtime_error, saying which step, where no Hopf point with the l1 wanted is found or the
// family does not turn inside the window.
GeneralizedHopfFold fold_of_cycles_from_generalized_hopf(const OdeSystem& system,
                                                         const GeneralizedHopfPoint& gh,
                                                         const GeneralizedHopfOptions& options,
                                                         const ContinuationCallbacks& family = {},
                                                         const CurveCallbacks& callbacks = {});

}  // namespace sympathy
