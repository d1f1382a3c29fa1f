#include "sympathy/core/reduced_system.hpp"

#include <vector>

#include "nested_scratch.hpp"

namespace sympathy {

ReducedSystem::ReducedSystem(const OdeSystem& system, const InvariantSubspace& subspace)
    : SystemOver(system), coordinates_(subspace.coordinates(system.dimension())) {}

std::vector<std::string> ReducedSystem::state_names() const {
  const auto names = system_.state_names();
  std::vector<std::string> out;
  for (int r : coordinates_.representative) out.push_back(names[r]);
  return out;
}

Eigen::VectorXd ReducedSystem::embed(const double* y) const {
  return coordinates_.embed(Eigen::Map<const Eigen::VectorXd>(y, dimension()));
}

namespace {

// The whole state's temporaries of a call, kept per thread (NestedScratch: a restriction of a
// restriction re-enters): the transient and plain runs in a subspace call rhs at every stage,
// the rough Newton in it the variational equations.
struct ReducedScratch {
  Eigen::VectorXd z, dz;
  Eigen::MatrixXd in, result;
  std::vector<const double*> in_columns;
  std::vector<double*> out_columns;
};

// z = P y into the scratch, dz sized with it.
void embed_state(const InvariantSubspace::Coordinates& k, const double* y, ReducedScratch& s) {
  const int n = static_cast<int>(k.coordinate.size());
  s.z.resize(n);
  s.dz.resize(n);
  k.embed_into(y, s.z.data());
}

// dy = R dz: the whole right-hand side read off at the representatives.
void read_off(const InvariantSubspace::Coordinates& k, const Eigen::VectorXd& dz, double* dy) {
  for (std::size_t i = 0; i < k.representative.size(); ++i) dy[i] = dz[k.representative[i]];
}

}  // namespace

void ReducedSystem::rhs(double t, const double* y, const double* p, double* dy) const {
  const detail::NestedScratch<ReducedScratch> s;
  embed_state(coordinates_, y, *s);
  system_.rhs(t, s->z.data(), p, s->dz.data());
  read_off(coordinates_, s->dz, dy);
}

void ReducedSystem::jacobian(double t, const double* y, const double* p,
                             Eigen::MatrixXd& jac) const {
  // R J P, from the whole Jacobian's columns: column k of J P sums the columns of the components
  // that coordinate k stands for.
  const Eigen::VectorXd z = embed(y);
  Eigen::MatrixXd full(z.size(), z.size());
  system_.jacobian(t, z.data(), p, full);
  const int d = dimension();
  jac.setZero(d, d);
  for (int c = 0; c < z.size(); ++c) {
    const int k = coordinates_.coordinate[c];
    if (k < 0) continue;
    for (int i = 0; i < d; ++i)
      jac(i, k) += coordinates_.sign[c] * full(coordinates_.representative[i], c);
  }
}

void ReducedSystem::variational_rhs(double t, const double* y, const double* p, int columns,
                                    const double* const* S, double* const* out,
                                    std::span<const int> parameters) const {
  variational(t, y, p, columns, S, out, parameters, nullptr);
}

void ReducedSystem::rhs_and_variational(double t, const double* y, const double* p, double* dy,
                                        int columns, const double* const* S, double* const* out,
                                        std::span<const int> parameters) const {
  variational(t, y, p, columns, S, out, parameters, dy);
}

// P S's columns through the whole system's variational equations (with f, in the one call that
// gives both where `dy` is asked for: a dual-number model evaluates once), read off at the
// representatives.
void ReducedSystem::variational(double t, const double* y, const double* p, int columns,
                                const double* const* S, double* const* out,
                                std::span<const int> parameters, double* dy) const {
  const detail::NestedScratch<ReducedScratch> s;
  embed_state(coordinates_, y, *s);
  const int n = static_cast<int>(s->z.size()), d = dimension();
  s->in.resize(n, columns);
  s->result.resize(n, columns);
  s->in_columns.resize(columns);
  s->out_columns.resize(columns);
  for (int j = 0; j < columns; ++j) {
    coordinates_.embed_into(S[j], s->in.col(j).data());
    s->in_columns[j] = s->in.col(j).data();
    s->out_columns[j] = s->result.col(j).data();
  }
  if (dy) {
    system_.rhs_and_variational(t, s->z.data(), p, s->dz.data(), columns, s->in_columns.data(),
                                s->out_columns.data(), parameters);
    read_off(coordinates_, s->dz, dy);
  } else {
    system_.variational_rhs(t, s->z.data(), p, columns, s->in_columns.data(), s->out_columns.data(),
                            parameters);
  }
  for (int j = 0; j < columns; ++j)
    for (int k = 0; k < d; ++k) out[j][k] = s->result(coordinates_.representative[k], j);
}

void ReducedSystem::parameter_derivative(double t, const double* y, const double* p, int parameter,
                                         double* dfdp) const {
  const Eigen::VectorXd z = embed(y);
  Eigen::VectorXd full(z.size());
  system_.parameter_derivative(t, z.data(), p, parameter, full.data());
  for (int k = 0; k < dimension(); ++k) dfdp[k] = full[coordinates_.representative[k]];
}

std::vector<SteepZone> ReducedSystem::steep_zones(const double* p) const {
  std::vector<SteepZone> zones;
  for (SteepZone zone : system_.steep_zones(p)) {
    const int k = coordinates_.coordinate[zone.component];
    if (k < 0) continue;
    // Several components tied to one coordinate share its zone: keep one.
    bool seen = false;
    for (const auto& z : zones) seen = seen || z.component == k;
    if (seen) continue;
    zone.component = k;
    zones.push_back(zone);
  }
  return zones;
}

void ReducedSystem::switching_functions(double t, const double* y, const double* p,
                                        double* g) const {
  const Eigen::VectorXd z = embed(y);
  system_.switching_functions(t, z.data(), p, g);
}

std::unique_ptr<OdeSystem> restrict_system(const OdeSystem& system,
                                           const InvariantSubspace& subspace) {
  if (auto own = system.restricted(subspace)) return own;
  return std::make_unique<ReducedSystem>(system, subspace);
}

}  // namespace sympathy
