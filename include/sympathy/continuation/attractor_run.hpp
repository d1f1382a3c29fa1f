// One trajectory to its fate among named attractors (attractors.hpp): stopped as soon as a
// convergence certificate says it converges to one of them; otherwise, at its end, Newton from
// where it ended (with the period of its first return) tells which orbit it ended near: a known
// one (reached too slowly to be certified), a stable orbit none of them is (a new attractor, named
// afterwards by name_new_attractors), or none (still moving: an unstable orbit it lingers near,
// chaotic motion, a transient longer than the run); an end at rest is a stable or unstable
// equilibrium; an end that circles an orbit with a complex pair of multipliers outside the unit
// circle (the torus born at its Neimark-Sacker point) at a steady distance is a torus, with its
// mean rotation number.
#pragma once

#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/attractors.hpp"
#include "sympathy/core/flow.hpp"

namespace sympathy {

struct AttractorRunOptions {
  double t_end = 300.0;  // the longest run
  // The sampling interval the certificates read the trajectory at; a period should hold 20 or
  // more (the section's Hermite interpolation: 3e-5 relative at 20 a period).
  double dt = 0.01;
  FlowOptions flow;  // the runs' integrator
  AttractorOptions attractors;

  OptionCheck validate() const;
};

enum class Fate {
  Certified,    // stopped early, certified to converge to `attractor`
  Reached,      // at t_end, Newton from its end converged to `attractor`'s orbit
  NewOrbit,     // at t_end, near a stable orbit that is none of the attractors (`orbit`)
  Equilibrium,  // at t_end, at rest: at a stable equilibrium (`equilibrium_state`; `attractor`
                // where it is one of the attractors)
  Torus,        // at t_end, on an invariant torus around an orbit whose leading multipliers are
                // a complex pair outside the unit circle (`orbit`), its `rotation_number`
  Unresolved,   // at t_end, near no stable orbit or equilibrium (`note` says what it found)
  Failed,       // the integration failed (`note`)
};
std::string to_string(Fate f);  // "certified", "reached", "new orbit", ...

struct AttractorFate {
  Fate fate = Fate::Unresolved;
  int attractor = -1;  // Certified, Reached (Equilibrium): the index among the attractors given
  double stopped_at = 0.0;
  Eigen::VectorXd end_state;
  std::optional<PeriodicOrbit> orbit;  // NewOrbit: the orbit Newton found
  // NewOrbit: its neighbourhood, computed once to judge it stable (name_new_attractors keeps it).
  std::shared_ptr<const OrbitNeighbourhood> neighbourhood;
  Eigen::VectorXd equilibrium_state;      // Equilibrium
  double rotation_number = std::nan("");  // Torus: in [0, 1), turns a return about the orbit
  std::string note;                       // Unresolved, Failed: why
};

// Runs the trajectory from `start` at parameter values `p` to options.t_end or to a certificate
// of one of `attractors` (all at p). No result when `stop` became true during it.
std::optional<AttractorFate> run_to_attractor(const OdeSystem& system, const ParameterValues& p,
                                              const Eigen::VectorXd& start,
                                              const std::vector<Attractor>& attractors,
                                              const AttractorRunOptions& options,
                                              const std::atomic<bool>* stop = nullptr);

// The new attractors among `fates` (all at p): the stable orbits of NewOrbit fates and the
// equilibria of Equilibrium fates that are none of the attractors, named in the order of the runs
// that found them ("new 1", "new 2", ..., an equilibrium "new 3 (at rest)"; the same orbit found by
// two runs once, judged by same_orbit; numbered from `first`), each with the symmetry it keeps: the
// description of the smallest of `symmetries` its orbit lies in (to 1e-8 of its size: "new 1 (x =
// 0, th2 = -th1)"); each NewOrbit fate's `attractor` is set to its index in the list returned plus
// `offset` (the caller appends the list to its attractors). Deterministic: it depends on the fates'
// order alone, not on which run finished first.
std::vector<Attractor> name_new_attractors(const OdeSystem& system,
                                           std::vector<AttractorFate>& fates,
                                           const AttractorOptions& options, int offset,
                                           int first = 1,
                                           const std::vector<InvariantSubspace>& symmetries = {});

}  // namespace sympathy
