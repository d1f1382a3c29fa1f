#include "sympathy/core/invariant_subspace.hpp"

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
