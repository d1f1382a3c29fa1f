#include "sympathy/continuation/symmetry_reduction.hpp"

#include "sympathy/core/reduced_system.hpp"

namespace sympathy {

std::optional<SymmetryReduction> symmetry_reduction(const OdeSystem& system,
                                                    const ParameterValues& p,
                                                    const InvariantSubspace& subspace) {
  const auto& symmetry = subspace.symmetry();
  if (!symmetry || symmetry->units.size() < 3) return std::nullopt;
  const int n = system.dimension();
  // Far above rounding (1e-16); a detuning that moves f by less changes the orbit and its
  // multipliers by less than their own accuracy (about 1e-9 at rtol 1e-11).
  constexpr double kDefect = 1e-12;
  if (symmetry->defect(system, p, Eigen::VectorXd::Constant(n, 0.5)) > kDefect) return std::nullopt;
  const auto& units = symmetry->units;
  std::vector<ComponentRelation> relations;
  for (std::size_t u = 2; u < units.size(); ++u)
    for (std::size_t k = 0; k < units[u].size(); ++k)
      relations.push_back({units[u][k], units[1][k], 1.0});
  SymmetryReduction r;
  r.block = InvariantSubspace(n, relations);
  r.coordinates = r.block.coordinates(n);
  r.system = restrict_system(system, r.block);
  r.subspace = subspace.within(r.block, n);
  r.copies = static_cast<int>(units.size()) - 1;
  r.description = "S_" + std::to_string(units.size()) + " symmetry of " + symmetry->description +
                  ": one against the other " + std::to_string(r.copies) +
                  ", its difference block standing for all " + std::to_string(r.copies);
  return r;
}

PeriodicOrbit lift(PeriodicOrbit reduced, const SymmetryReduction& reduction,
                   const InvariantSubspace& subspace, const FloquetOptions& options) {
  reduced.state0 = reduction.coordinates.embed(reduced.state0);
  reduced.subspace = subspace;
  reduced.floquet = repeat_breaking(std::move(reduced.floquet), reduction.copies, options);
  reduced.reduction = reduction.description;
  return reduced;
}

}  // namespace sympathy
