#include "sympathy/continuation/symmetry_reduction.hpp"

#include "sympathy/continuation/detection.hpp"
#include "sympathy/core/hybrid_system.hpp"
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
  // A piecewise-smooth system's generic restriction declares no saltation: no reduction.
  if (!carries_sensitivities(*r.system)) return std::nullopt;
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

namespace {

// Shooting unknowns (m segment states, then the period, then possibly the parameter) embedded.
Eigen::VectorXd embed_unknowns(const Eigen::VectorXd& x, const SymmetryReduction& r) {
  const int d = r.coordinates.size();
  if (x.size() == 0) return x;
  const int n = static_cast<int>(r.coordinates.coordinate.size());
  const int m = static_cast<int>(x.size()) / d;  // whole segments; the rest is period (and p)
  const int rest = static_cast<int>(x.size()) - m * d;
  Eigen::VectorXd z(m * n + rest);
  for (int j = 0; j < m; ++j) z.segment(j * n, n) = r.coordinates.embed(x.segment(j * d, d));
  z.tail(rest) = x.tail(rest);
  return z;
}

Eigen::VectorXd embed_state(const Eigen::VectorXd& y, const SymmetryReduction& r) {
  return y.size() == r.coordinates.size() ? r.coordinates.embed(y) : y;
}

}  // namespace

ContinuationPoint lift(ContinuationPoint point, const SymmetryReduction& reduction,
                       const InvariantSubspace& subspace, const FloquetOptions& options) {
  point.orbit = lift(std::move(point.orbit), reduction, subspace, options);
  point.unknowns = embed_unknowns(point.unknowns, reduction);
  point.tangent = embed_unknowns(point.tangent, reduction);
  point.section.through = embed_state(point.section.through, reduction);
  point.section.normal = embed_state(point.section.normal, reduction);
  return point;
}

Bifurcation lift(Bifurcation event, const SymmetryReduction& reduction,
                 const FloquetOptions& options) {
  event.floquet = repeat_breaking(std::move(event.floquet), reduction.copies, options);
  event.state0 = embed_state(event.state0, reduction);
  event.unknowns = embed_unknowns(event.unknowns, reduction);
  event.tangent = embed_unknowns(event.tangent, reduction);
  if (event.symmetry == SymmetryKind::Breaking && reduction.copies > 1) {
    // Each breaking crossing of the block is one in each of its copies, at the same value.
    const std::string before = together_note(event.type, event.multiplicity);
    event.multiplicity *= reduction.copies;
    const std::string after = together_note(event.type, event.multiplicity);
    if (!before.empty() && event.note.rfind(before, 0) == 0)
      event.note.replace(0, before.size(), after);
    else
      event.note = after + (event.note.empty() ? "" : "; " + event.note);
  }
  return event;
}

Branch lift(Branch branch, const SymmetryReduction& reduction, const OdeSystem& system,
            const InvariantSubspace& subspace) {
  const FloquetOptions& options = branch.options.orbit.floquet;
  for (auto& p : branch.points) p = lift(std::move(p), reduction, subspace, options);
  for (auto& e : branch.events) e = lift(std::move(e), reduction, options);
  branch.state_names = system.state_names();
  return branch;
}

}  // namespace sympathy
