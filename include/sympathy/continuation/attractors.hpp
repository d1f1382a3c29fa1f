// The attractors a trajectory may end on, named by what continuation found: the stable periodic
// orbits that the given branches hold at one parameter value, each with its branch's name and
// the branch point nearest it; those of the previous value of a walk along the parameter,
// continued to this one by Newton (so that an attractor keeps its name from value to value
// because it is the same orbit continued, not because a label says so); and whether two orbits
// are one.
//
// Everything here is generic: a system, branches and their names. Nothing knows of metronomes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/convergence_certificate.hpp"
#include "sympathy/continuation/equilibrium.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

// A stable periodic orbit at given parameter values, with what names it.
struct Attractor {
  std::string name;    // the branch's (with " (k)" where a branch holds more than one), or "new k"
  std::string branch;  // the branch it lies on; empty: found by runs that ended on it
  int point = -1;      // the index of the branch's point nearest it (-1: none)
  PeriodicOrbit orbit;
  std::shared_ptr<const OrbitNeighbourhood> neighbourhood;  // what certificates and matching need
  // A stable equilibrium instead of an orbit (not empty: its state; orbit and neighbourhood
  // unused): runs that end at rest there count under its name.
  Eigen::VectorXd rest;
  bool at_rest() const { return rest.size() > 0; }
};

// Whether `z` is the state of the equilibrium attractor `a` (to 1e-6 of the state's size).
bool same_rest(const Attractor& a, const Eigen::VectorXd& z);
// Whether Newton's equilibrium converged and is stable: every eigenvalue's real part below -1e-6
// times the largest |lambda| (not marginally).
bool stable_equilibrium(const Equilibrium& e);

// A branch with the name it goes by (a study's entry: "anti", "born").
struct NamedBranch {
  std::string name;
  const Branch* branch = nullptr;
};
// A branch of equilibria with the name it goes by (a study's [[equilibria]] entry: "origin").
struct NamedEquilibria {
  std::string name;
  const EquilibriumBranch* branch = nullptr;
};

struct AttractorOptions {
  OrbitOptions orbit;              // Newton's, from a branch's interpolated orbit or a run's end
  CertificateOptions certificate;  // the margin decides what counts as stable
  double match_tolerance = 1e-4;   // two orbits are one: see same_orbit
  double period_tolerance = 1e-5;  // relative

  OptionCheck validate() const;
};

// Whether `orbit` is the orbit of `neighbourhood` (both at the same parameter values): their
// periods agree to period_tolerance (relative) and `orbit`, followed over 1.25 of its period
// from its point (400 samples a period), returns to the other's section within match_tolerance
// of its point, in the eigen-coordinates of ConvergenceCertificate (a distance relative to the
// orbit's amplitude per state; Newton's orbits agree to about 1e-8 in it, the section's
// interpolation adds 3e-9 at 400 samples a period; orbits that differ do by far more: the two
// orbits w = +-0.5 of the pitchfork of cycles at mu = 0.25 by 2 in it).
bool same_orbit(const OdeSystem& system, const PeriodicOrbit& orbit,
                const OrbitNeighbourhood& neighbourhood, const AttractorOptions& options);

// The stable orbits (with the certificate's margin) that `branches` hold at parameter values `p`
// (the branches' parameter set to its value in p): on every pair of neighbouring points whose
// parameters bracket that value (not both unstable), the orbit interpolated linearly between them
// and corrected by Newton at p, in the subspace of the point nearer it. In the branches' order,
// then along each branch; an orbit found twice (where a branch folds back onto itself, or two
// branches share a stretch) once, under its first name. Integration failures are no orbit.
std::vector<Attractor> attractors_on_branches(const OdeSystem& system, const ParameterValues& p,
                                              const std::vector<NamedBranch>& branches,
                                              const AttractorOptions& options);

// The stable equilibria (stable_equilibrium) that `branches` of equilibria hold at parameter
// values `p`, as attractors at rest: on every pair of neighbouring points whose parameters
// bracket the value (not both unstable), Newton on f = 0 at p from the state interpolated between
// them; named as attractors_on_branches names orbits (the entry's name, " (k)" where one branch
// holds more than one), each once.
std::vector<Attractor> attractors_at_rest_on_branches(const OdeSystem& system,
                                                      const ParameterValues& p,
                                                      const std::vector<NamedEquilibria>& branches,
                                                      const AttractorOptions& options);

// The attractors of another parameter value continued to `p`: Newton from each orbit (its point
// and period) at p, kept with its name where it converges to a stable orbit (with the
// certificate's margin); Newton on f = 0 from each equilibrium, kept where it converges to a
// stable one. Those that do not are gone (the attractor ended between the values).
std::vector<Attractor> continue_attractors(const OdeSystem& system, const ParameterValues& p,
                                           const std::vector<Attractor>& previous,
                                           const AttractorOptions& options);

// The attractors at a value of a walk: `on_branches` (attractors_on_branches and
// attractors_at_rest_on_branches at it), each taking the name of the continued attractor
// (continue_attractors from the previous value) that is the same orbit or equilibrium, then the
// continued ones that are on no branch there, with their names. A branch's attractor whose own name
// another one now has gets the next free " (k)".
std::vector<Attractor> merge_attractors(const OdeSystem& system, std::vector<Attractor> on_branches,
                                        std::vector<Attractor> continued,
                                        const AttractorOptions& options);

}  // namespace sympathy
