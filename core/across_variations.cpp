#include "sympathy/core/across_variations.hpp"

#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sympathy {

namespace {

Eigen::MatrixXd breaking_basis_of(const InvariantSubspace& subspace, int dimension) {
  const auto g = subspace.reflection(dimension);
  if (!g)
    throw std::invalid_argument(
        "across variations: the subspace is not the fixed space of a reflection (" +
        subspace.description() + ")");
  return g->breaking_basis();
}

}  // namespace

AcrossVariations::AcrossVariations(const OdeSystem& system, const InvariantSubspace& subspace)
    : SystemOver(system),
      reduced_(system, subspace),
      coordinates_(reduced_.coordinates()),
      breaking_(breaking_basis_of(subspace, system.dimension())) {}

Eigen::VectorXd AcrossVariations::start(const Eigen::VectorXd& z0) const {
  const int r = inside(), a = across();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(dimension());
  w.head(r) = coordinates_.restrict(z0);
  for (int j = 0; j < a; ++j) w[r + j * a + j] = 1.0;
  return w;
}

Eigen::MatrixXd AcrossVariations::block(const Eigen::VectorXd& w) const {
  const int a = across();
  return Eigen::Map<const Eigen::MatrixXd>(w.data() + inside(), a, a);
}

std::vector<std::string> AcrossVariations::state_names() const {
  std::vector<std::string> names = reduced_.state_names();
  for (int j = 0; j < across(); ++j)
    for (int i = 0; i < across(); ++i) {
      std::string name = "U";  // built by appending: GCC 12 warns (-Wrestrict) on "U" + string
      name += std::to_string(i + 1);
      name += '_';
      name += std::to_string(j + 1);
      names.push_back(std::move(name));
    }
  return names;
}

Eigen::VectorXd AcrossVariations::embed(const double* w) const {
  return coordinates_.embed(Eigen::Map<const Eigen::VectorXd>(w, inside()));
}

void AcrossVariations::rhs(double t, const double* w, const double* p, double* dw) const {
  const int r = inside(), a = across(), n = system_.dimension();
  // Scratch per thread, kept between calls (one system serves several threads, so not members):
  // malloc and free of six temporaries a call were 6% of the fast preset's profile on the
  // anti-phase branch; without them the branch took 0.29 s instead of 0.30.
  thread_local Scratch s;
  s.z.resize(n);
  s.dz.resize(n);
  s.in.resize(n, a);
  s.out.resize(n, a);
  s.in_columns.resize(a);
  s.out_columns.resize(a);
  const auto& k = coordinates_;
  for (int c = 0; c < n; ++c) s.z[c] = k.coordinate[c] < 0 ? 0.0 : k.sign[c] * w[k.coordinate[c]];
  // f and U' = C^T J C U: J applied to the columns C U_j, all in one call of the model (one
  // dual-number evaluation for f and all a columns; OdeSystem::rhs_and_variational).
  const Eigen::Map<const Eigen::MatrixXd> U(w + r, a, a);
  s.in.noalias() = breaking_ * U;
  for (int j = 0; j < a; ++j) {
    s.in_columns[j] = s.in.col(j).data();
    s.out_columns[j] = s.out.col(j).data();
  }
  system_.rhs_and_variational(t, s.z.data(), p, s.dz.data(), a, s.in_columns.data(),
                              s.out_columns.data(), {});
  for (int i = 0; i < r; ++i) dw[i] = s.dz[k.representative[i]];
  Eigen::Map<Eigen::MatrixXd>(dw + r, a, a).noalias() = breaking_.transpose() * s.out;
}

void AcrossVariations::jacobian(double t, const double* w, const double* p,
                                Eigen::MatrixXd& jac) const {
  const int r = inside(), a = across(), n = system_.dimension();
  const Eigen::VectorXd z = embed(w);
  Eigen::MatrixXd inner;
  reduced_.jacobian(t, w, p, inner);
  Eigen::MatrixXd full(n, n);
  system_.jacobian(t, z.data(), p, full);
  const Eigen::MatrixXd A = breaking_.transpose() * full * breaking_;
  jac.setZero(dimension(), dimension());
  jac.topLeftCorner(r, r) = inner;
  for (int j = 0; j < a; ++j) jac.block(r + j * a, r + j * a, a, a) = A;
}

void AcrossVariations::variational_rhs(double t, const double* w, const double* p, int columns,
                                       const double* const* S, double* const* out,
                                       std::span<const int> parameters) const {
  if (!parameters.empty())
    throw std::invalid_argument("across variations carry no parameter sensitivities");
  Eigen::MatrixXd jac;
  jacobian(t, w, p, jac);
  for (int j = 0; j < columns; ++j)
    Eigen::Map<Eigen::VectorXd>(out[j], dimension()) =
        jac * Eigen::Map<const Eigen::VectorXd>(S[j], dimension());
}

void AcrossVariations::parameter_derivative(double, const double*, const double*, int,
                                            double*) const {
  throw std::invalid_argument("across variations carry no parameter sensitivities");
}

std::vector<SteepZone> AcrossVariations::steep_zones(const double* p) const {
  return reduced_.steep_zones(p);
}

void AcrossVariations::switching_functions(double t, const double* w, const double* p,
                                           double* g) const {
  reduced_.switching_functions(t, w, p, g);
}

}  // namespace sympathy
