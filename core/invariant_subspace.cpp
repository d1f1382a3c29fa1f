#include "sympathy/core/invariant_subspace.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <stdexcept>
#include <utility>

namespace sympathy {

InvariantSubspace::InvariantSubspace(int dimension, const std::vector<ComponentRelation>& relations,
                                     std::string description)
    : description_(std::move(description)) {
  // Union-find with a sign per node relative to its parent.
  std::vector<int> parent(dimension);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<double> sign(dimension, 1.0);  // z_i = sign_i * z_parent(i)
  std::vector<bool> zero(dimension, false);
  auto find = [&](int i) {
    double s = 1.0;
    int r = i;
    while (parent[r] != r) {
      s *= sign[r];
      r = parent[r];
    }
    return std::pair{r, s};
  };
  auto check = [&](int c) {
    if (c < 0 || c >= dimension)
      throw std::invalid_argument("invariant relation names component " + std::to_string(c) +
                                  " of a state of dimension " + std::to_string(dimension));
  };
  std::vector<bool> involved(dimension, false);
  for (const auto& r : relations) {
    check(r.component);
    involved[r.component] = true;
    auto [ra, sa] = find(r.component);
    if (r.other < 0) {
      zero[ra] = true;
      continue;
    }
    check(r.other);
    involved[r.other] = true;
    auto [rb, sb] = find(r.other);
    // z_a = s z_b with z_a = sa z_ra, z_b = sb z_rb: z_ra = (s sb / sa) z_rb.
    const double rel = r.sign * sb / sa;
    if (ra == rb) {
      if (rel < 0) zero[ra] = true;  // z = -z: zero
      continue;
    }
    parent[ra] = rb;
    sign[ra] = rel;
    if (zero[ra]) zero[rb] = true;
  }
  std::vector<int> group_of(dimension, -1);
  for (int i = 0; i < dimension; ++i) {
    if (!involved[i]) continue;
    auto [root, s] = find(i);
    if (group_of[root] < 0) {
      group_of[root] = static_cast<int>(groups_.size());
      groups_.push_back({});
    }
    auto& g = groups_[group_of[root]];
    g.members.push_back({i, s});
    g.zero = g.zero || zero[root];
  }
}

namespace {

// The eigenvectors of an orthogonal projector with eigenvalue 1 (`inside`) or 0: its range or
// its null space, orthonormal. The projector's eigenvalues are 0 and 1 to rounding; 1/2 splits
// them.
Eigen::MatrixXd projector_eigenvectors(const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>& eig,
                                       bool inside) {
  std::vector<int> chosen;
  for (int i = 0; i < eig.eigenvalues().size(); ++i)
    if ((eig.eigenvalues()[i] > 0.5) == inside) chosen.push_back(i);
  Eigen::MatrixXd q(eig.eigenvectors().rows(), static_cast<int>(chosen.size()));
  for (std::size_t k = 0; k < chosen.size(); ++k)
    q.col(static_cast<int>(k)) = eig.eigenvectors().col(chosen[k]);
  return q;
}

}  // namespace

Eigen::MatrixXd InvariantSubspace::projector(int dimension) const {
  Eigen::MatrixXd p(dimension, dimension);
  for (int j = 0; j < dimension; ++j) p.col(j) = project(Eigen::VectorXd::Unit(dimension, j));
  return p;
}

InvariantSubspace::Bases InvariantSubspace::bases(int dimension) const {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(projector(dimension));
  return {projector_eigenvectors(eig, true), projector_eigenvectors(eig, false)};
}

Eigen::MatrixXd InvariantSubspace::basis(int dimension) const {
  return bases(dimension).inside;
}

Eigen::MatrixXd InvariantSubspace::complement(int dimension) const {
  return bases(dimension).across;
}

Eigen::VectorXd InvariantSubspace::project(const Eigen::VectorXd& z) const {
  Eigen::VectorXd p = z;
  for (const auto& g : groups_) {
    double mean = 0.0;
    if (!g.zero) {
      for (const auto& m : g.members) mean += m.sign * z[m.component];
      mean /= static_cast<double>(g.members.size());
    }
    for (const auto& m : g.members) p[m.component] = m.sign * mean;
  }
  return p;
}

InvariantSubspace InvariantSubspace::fixed_by(const PermutationSymmetry& symmetry, int dimension,
                                              std::string description) {
  std::vector<ComponentRelation> relations;
  const auto& units = symmetry.units;
  for (std::size_t u = 1; u < units.size(); ++u) {
    if (units[u].size() != units[0].size())
      throw std::invalid_argument("permutation symmetry: units of different sizes");
    for (std::size_t k = 0; k < units[u].size(); ++k)
      relations.push_back({units[u][k], units[0][k], 1.0});
  }
  InvariantSubspace s(dimension, relations, std::move(description));
  s.symmetry_ = symmetry;
  return s;
}

InvariantSubspace InvariantSubspace::with_symmetry(PermutationSymmetry symmetry,
                                                   int dimension) const {
  if (!same_as(fixed_by(symmetry, dimension, ""), dimension))
    throw std::invalid_argument("the subspace {" + description_ +
                                "} is not the one that every permutation of " +
                                symmetry.description + " keeps");
  InvariantSubspace s = *this;
  s.symmetry_ = std::move(symmetry);
  return s;
}

bool InvariantSubspace::same_as(const InvariantSubspace& other, int dimension) const {
  for (int j = 0; j < dimension; ++j) {
    const Eigen::VectorXd e = Eigen::VectorXd::Unit(dimension, j);
    if ((project(e) - other.project(e)).cwiseAbs().maxCoeff() > 1e-12) return false;
  }
  return true;
}

InvariantSubspace::Coordinates InvariantSubspace::coordinates(int dimension) const {
  Coordinates c;
  c.coordinate.assign(dimension, -1);
  c.sign.assign(dimension, 1.0);
  std::vector<int> group_of(dimension, -1);
  for (std::size_t g = 0; g < groups_.size(); ++g)
    for (const auto& m : groups_[g].members) {
      if (m.component >= dimension)
        throw std::invalid_argument("invariant subspace: component " + std::to_string(m.component) +
                                    " outside a state of dimension " + std::to_string(dimension));
      group_of[m.component] = static_cast<int>(g);
    }
  // Members are in increasing order of component, so a group's first member comes first.
  for (int i = 0; i < dimension; ++i) {
    if (group_of[i] < 0) {
      c.coordinate[i] = c.size();
      c.representative.push_back(i);
      continue;
    }
    const Group& g = groups_[group_of[i]];
    if (g.zero) {
      c.sign[i] = 0.0;
      continue;
    }
    const Member& first = g.members.front();
    if (first.component == i) {
      c.coordinate[i] = c.size();
      c.representative.push_back(i);
    } else {
      c.coordinate[i] = c.coordinate[first.component];
      const auto self = std::find_if(g.members.begin(), g.members.end(),
                                     [i](const Member& m) { return m.component == i; });
      c.sign[i] = self->sign * first.sign;  // signs are +-1
    }
  }
  return c;
}

Eigen::VectorXd InvariantSubspace::Coordinates::embed(const Eigen::VectorXd& y) const {
  Eigen::VectorXd z(static_cast<int>(coordinate.size()));
  embed_into(y.data(), z.data());
  return z;
}

Eigen::VectorXd InvariantSubspace::Coordinates::restrict(const Eigen::VectorXd& z) const {
  Eigen::VectorXd y(size());
  for (int k = 0; k < size(); ++k) y[k] = z[representative[k]];
  return y;
}

Eigen::MatrixXd InvariantSubspace::Coordinates::embedding() const {
  Eigen::MatrixXd P = Eigen::MatrixXd::Zero(static_cast<int>(coordinate.size()), size());
  for (int c = 0; c < P.rows(); ++c)
    if (coordinate[c] >= 0) P(c, coordinate[c]) = sign[c];
  return P;
}

Eigen::MatrixXd InvariantSubspace::Coordinates::restriction() const {
  Eigen::MatrixXd R = Eigen::MatrixXd::Zero(size(), static_cast<int>(coordinate.size()));
  for (int k = 0; k < size(); ++k) R(k, representative[k]) = 1.0;
  return R;
}

InvariantSubspace InvariantSubspace::within(const InvariantSubspace& larger, int dimension) const {
  const Coordinates outer = larger.coordinates(dimension);
  const Coordinates inner = coordinates(dimension);
  // Larger's coordinate k is component r_k; here r_k = sign * u_(inner coordinate). Tie the
  // coordinates that share an inner coordinate; those of zero components are zero.
  std::vector<ComponentRelation> relations;
  std::vector<int> first(inner.size(), -1);
  for (int k = 0; k < outer.size(); ++k) {
    const int r = outer.representative[k];
    const int u = inner.coordinate[r];
    if (u < 0) {
      relations.push_back({k, -1, 1.0});
    } else if (first[u] < 0) {
      first[u] = k;
    } else {
      const int k0 = first[u];
      relations.push_back({k, k0, inner.sign[r] * inner.sign[outer.representative[k0]]});
    }
  }
  InvariantSubspace s(outer.size(), relations, description_);
  // Every state of this subspace must be a state of `larger` with these relations.
  for (int j = 0; j < dimension; ++j) {
    const Eigen::VectorXd z = project(Eigen::VectorXd::Unit(dimension, j));
    if ((outer.embed(s.project(outer.restrict(z))) - z).cwiseAbs().maxCoeff() > 1e-12)
      throw std::invalid_argument("the subspace {" + description_ + "} does not lie in {" +
                                  larger.description_ + "}");
  }
  return s;
}

Eigen::VectorXd Reflection::apply(const Eigen::VectorXd& z) const {
  Eigen::VectorXd out(z.size());
  for (int i = 0; i < z.size(); ++i) out[i] = sign[i] * z[image[i]];
  return out;
}

Eigen::MatrixXd Reflection::breaking_basis() const {
  const int n = static_cast<int>(image.size());
  std::vector<Eigen::VectorXd> columns;
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
    if (image[i] == i && sign[i] < 0.0) {
      v[i] = 1.0;
    } else if (image[i] > i) {
      v[i] = std::sqrt(0.5);
      v[image[i]] = -sign[i] * std::sqrt(0.5);
    } else {
      continue;
    }
    columns.push_back(std::move(v));
  }
  Eigen::MatrixXd basis(n, static_cast<int>(columns.size()));
  for (std::size_t j = 0; j < columns.size(); ++j) basis.col(static_cast<int>(j)) = columns[j];
  return basis;
}

std::optional<Reflection> InvariantSubspace::reflection(int dimension) const {
  if (groups_.empty()) return std::nullopt;
  Reflection g;
  g.image.resize(dimension);
  std::iota(g.image.begin(), g.image.end(), 0);
  g.sign.assign(dimension, 1.0);
  for (const Group& group : groups_) {
    if (group.members.size() > 2) return std::nullopt;
    if (group.zero) {
      for (const Member& m : group.members) g.sign[m.component] = -1.0;
      continue;
    }
    if (group.members.size() < 2) continue;  // a component tied to nothing: not moved
    // z_a = s_a z_r and z_b = s_b z_r: z_a = s_a s_b z_b, and g swaps them with that sign.
    const Member& a = group.members[0];
    const Member& b = group.members[1];
    const double s = a.sign * b.sign;
    g.image[a.component] = b.component;
    g.image[b.component] = a.component;
    g.sign[a.component] = s;
    g.sign[b.component] = s;
  }
  return g;
}

Eigen::VectorXd PermutationSymmetry::swapped(Eigen::VectorXd z, int a, int b) const {
  for (std::size_t k = 0; k < units[a].size(); ++k) std::swap(z[units[a][k]], z[units[b][k]]);
  return z;
}

double equivariance_defect(const OdeSystem& system, const ParameterValues& p,
                           const Eigen::VectorXd& scale,
                           const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd z(system.dimension());
    for (int i = 0; i < z.size(); ++i) z[i] = scale[i] * u(rng);
    const Eigen::VectorXd f = system.rhs(0.0, z, p);
    const double norm = std::max(f.cwiseAbs().maxCoeff(), 1e-300);
    worst = std::max(worst, (system.rhs(0.0, g(z), p) - g(f)).cwiseAbs().maxCoeff() / norm);
  }
  return worst;
}

double PermutationSymmetry::defect(const OdeSystem& system, const ParameterValues& p,
                                   const Eigen::VectorXd& scale) const {
  const int n = system.dimension();
  for (const auto& unit : units) {
    if (unit.size() != units.front().size())
      throw std::invalid_argument("permutation symmetry: units of different sizes");
    for (int c : unit)
      if (c < 0 || c >= n)
        throw std::invalid_argument("permutation symmetry: no state component " +
                                    std::to_string(c));
  }
  // The adjacent transpositions generate S_N.
  double worst = 0.0;
  for (int a = 0; a + 1 < static_cast<int>(units.size()); ++a)
    worst = std::max(worst, equivariance_defect(system, p, scale, [&](const Eigen::VectorXd& z) {
                       return swapped(z, a, a + 1);
                     }));
  return worst;
}

double InvariantSubspace::invariance_defect(const OdeSystem& system, const ParameterValues& p,
                                            const Eigen::VectorXd& scale) const {
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 4; ++trial) {
    Eigen::VectorXd z(system.dimension());
    for (int i = 0; i < z.size(); ++i) z[i] = scale[i] * u(rng);
    z = project(z);
    const Eigen::VectorXd f = system.rhs(0.0, z, p);
    const double norm = f.cwiseAbs().maxCoeff();
    if (norm > 0.0) worst = std::max(worst, (f - project(f)).cwiseAbs().maxCoeff() / norm);
  }
  return worst;
}

}  // namespace sympathy
