// The corrector of a continuation step: Newton on the bordered system (the shooting equations and
// the arclength condition <tau, Y - Y_from> = ds in the scaled norm), each iteration with the
// flow's sensitivities, so that the converged point's monodromy serves its stability and its
// tangent. Before it, quasi-Newton (Broyden) steps on plain residuals as accurate as those runs
// (ShootingProblem::residual, about a tenth of their cost) from a chord Jacobian do most of the
// work: they aim well below the tolerance, so that one integration with sensitivities at their
// end usually both confirms the point and gives its monodromy. Where predictions land on the
// branch (CorrectorOptions::derivatives_first) that integration comes first. A point is an orbit
// only where its residual is also within kOrbitClosure of its amplitude (closure_tolerance), as
// for Newton on a single orbit.
#pragma once

#include <limits>
#include <string>

#include "sympathy/continuation/branch_space.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

struct CorrectorOptions {
  int max_iterations = 7;
  int max_chord_steps = 6;  // quasi-Newton steps on plain integrations before the iterations
  double tolerance = 1e-9;  // |F|_inf: the attainable one (attainable_tolerance)
  // A quasi-Newton step whose residual is expected above this many tolerances (the guess's, or
  // the last one's times the contraction so far) takes it from a coarse plain run
  // (ShootingProblem::residual, a thousand times looser): the tolerance is about 1e-9 on the row
  // setup, and a coarse run's error 3e-8 to 1.6e-7 (at BDF rtol 1e-11 and the default preset),
  // below a fifth of the 1e-6 it then steers from (tests/cases/orbit_test.cpp). In-phase k-branch
  // at the default 0.99 -> 0.89 CPU s (medians of five; 266 000 -> 239 000 steps). 0: never.
  double coarse_above = 1e3;
  // The guess's residual expected: the first run is coarse only where this is above
  // coarse_above tolerances (a continuation passes its last step's; its own runs, whose guesses
  // land closer, 0). Where predictions come close, as on the Hopf normal form's branch, a coarse
  // first run would come out small and be run again tight: 123 -> 153 integrations there.
  double expected_residual = 0.0;
  // Start with an integration with sensitivities at the guess, and the quasi-Newton steps (if it
  // is not on the branch yet) from its Jacobian: for callers whose predictions have been landing
  // (saves the plain run before it).
  bool derivatives_first = false;
};

struct Correction {
  bool converged = false;
  std::string reason;                      // why not
  Eigen::VectorXd y;                       // (unknowns, parameter)
  ShootingProblem::Evaluation evaluation;  // at y, with sensitivities
  double residual = 0.0;                   // |F|_inf at y
  int iterations = 0;                      // with sensitivities
  int chord_steps = 0;                     // on plain integrations, before the iterations
  double guess_residual = std::numeric_limits<double>::quiet_NaN();  // |F|_inf at the guess
};

// Corrects `guess` onto the branch at arclength `step` from `from` along `tangent`, for the
// continued `parameter`, in the phase condition's `section` (the point `from`'s); `chord` (may be
// null) is the Jacobian the quasi-Newton steps start from, in that section.
Correction correct(ShootingProblem& problem, const PhaseSection& section, const BranchSpace& space,
                   int parameter, const CorrectorOptions& options, const Eigen::VectorXd& from,
                   const Eigen::VectorXd& tangent, double step, const Eigen::VectorXd& guess,
                   const Eigen::SparseMatrix<double>* chord);

}  // namespace sympathy
