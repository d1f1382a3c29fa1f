// Orbits of N identical units that all move alike, at the cost of a system of two units.
//
// Where an orbit's subspace V0 is the fixed space of permuting N >= 3 interchangeable units
// (InvariantSubspace::symmetry, declared by the case: identical metronomes in phase) and f keeps
// those permutations at the parameter values (checked: PermutationSymmetry::defect), the whole
// monodromy is block diagonal in the isotypic components of S_N: the symmetric motion (V0) and
// N - 1 identical blocks, one per independent difference between units. Both come from the
// subspace V1 in which every unit but the first moves alike (V1 contains V0): V1 is invariant
// too, and its monodromy holds V0's block and one copy of the difference block (the first unit
// against the rest). So the orbit is found and analysed as an orbit of the system restricted to
// V1 (restrict_system: for metronomes, a platform with two metronomes, the second standing for
// N - 1), lying in V0; its breaking multipliers are then repeated N - 1 times (repeat_breaking).
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "sympathy/continuation/branch.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/invariant_subspace.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

struct SymmetryReduction {
  InvariantSubspace block;                     // V1, in the whole space
  InvariantSubspace::Coordinates coordinates;  // V1's coordinates of the whole state
  std::unique_ptr<OdeSystem> system;           // the system restricted to V1
  InvariantSubspace subspace;                  // V0, in V1's coordinates
  int copies = 0;                              // N - 1: the difference block's multiplicity
  std::string description;                     // for reports
};

// The reduction of orbits in `subspace` at parameter values p, or nullopt where there is none:
// no declared symmetry, fewer than three units, or one f does not keep at p (relative defect
// above 1e-12). The reduction refers to `system`, which must outlive it.
std::optional<SymmetryReduction> symmetry_reduction(const OdeSystem& system,
                                                    const ParameterValues& p,
                                                    const InvariantSubspace& subspace);

// An orbit computed in the reduction (of its system, in its subspace) as an orbit of the whole
// system in `subspace`: its state embedded, its breaking multipliers repeated.
PeriodicOrbit lift(PeriodicOrbit reduced, const SymmetryReduction& reduction,
                   const InvariantSubspace& subspace, const FloquetOptions& options);

// The same for a branch point, an event (a breaking crossing is N - 1 crossings at once: its
// multiplicity times N - 1) and a whole branch computed in the reduction: states, unknowns,
// tangents and sections embedded (each shooting segment's state; the period and the parameter
// as they are), multipliers repeated, state names the whole system's.
ContinuationPoint lift(ContinuationPoint reduced, const SymmetryReduction& reduction,
                       const InvariantSubspace& subspace, const FloquetOptions& options);
Bifurcation lift(Bifurcation reduced, const SymmetryReduction& reduction,
                 const FloquetOptions& options);
Branch lift(Branch reduced, const SymmetryReduction& reduction, const OdeSystem& system,
            const InvariantSubspace& subspace);

}  // namespace sympathy
