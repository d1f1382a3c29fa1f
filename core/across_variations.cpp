#include "sympathy/core/across_variations.hpp"

#include <algorithm>
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

AcrossVariations::AcrossVariations(const OdeSystem& system, const InvariantSubspace& subspace,
                                   bool inside_block, int parameter)
    : SystemOver(system),
      reduced_(system, subspace),
      coordinates_(reduced_.coordinates()),
      breaking_(breaking_basis_of(subspace, system.dimension())),
      inside_block_(inside_block),
      parameter_(parameter) {
  for (int c = 0; c < breaking_.cols(); ++c)
    for (int i = 0; i < breaking_.rows(); ++i)
      if (breaking_(i, c) != 0.0) breaking_entries_.push_back({i, c, breaking_(i, c)});
  if (parameter >= 0 && !inside_block)
    throw std::invalid_argument("across variations: a parameter column needs V's own block");
}

Eigen::VectorXd AcrossVariations::start(const Eigen::VectorXd& z0) const {
  const int r = inside(), a = across();
  Eigen::VectorXd w = Eigen::VectorXd::Zero(dimension());
  w.head(r) = coordinates_.restrict(z0);
  if (inside_block_)
    for (int j = 0; j < r; ++j) w[r + j * r + j] = 1.0;
  for (int j = 0; j < a; ++j) w[across_offset() + j * a + j] = 1.0;
  return w;
}

Eigen::MatrixXd AcrossVariations::block(const Eigen::VectorXd& w) const {
  const int a = across();
  return Eigen::Map<const Eigen::MatrixXd>(w.data() + across_offset(), a, a);
}

Eigen::MatrixXd AcrossVariations::inside_block(const Eigen::VectorXd& w) const {
  if (!inside_block_) return {};
  return Eigen::Map<const Eigen::MatrixXd>(w.data() + inside(), inside(), inside());
}

Eigen::VectorXd AcrossVariations::parameter_column(const Eigen::VectorXd& w) const {
  if (parameter_ < 0) return {};
  return w.segment(column_offset(), inside());
}

std::vector<std::string> AcrossVariations::state_names() const {
  std::vector<std::string> names = reduced_.state_names();
  const int r = inside();
  if (inside_block_)
    for (int j = 0; j < r; ++j)
      for (int i = 0; i < r; ++i) {
        std::string name = "Y";
        name += std::to_string(i + 1);
        name += '_';
        name += std::to_string(j + 1);
        names.push_back(std::move(name));
      }
  if (parameter_ >= 0)
    for (int i = 0; i < r; ++i) {
      std::string name = "s";  // appended, as below
      name += std::to_string(i + 1);
      names.push_back(std::move(name));
    }
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
  const int own = inside_block_ ? r : 0, with_parameter = parameter_ >= 0 ? 1 : 0;
  const int columns = a + own + with_parameter;
  // Scratch per thread, kept between calls (one system serves several threads, so not members):
  // malloc and free of six temporaries a call were 6% of the fast preset's profile on the
  // anti-phase branch; without them the branch took 0.29 s instead of 0.30.
  thread_local Scratch s;
  if (s.in.rows() != n || s.in.cols() != columns) {  // resizing at every call: 1.2% of fast
    s.z.resize(n);
    s.dz.resize(n);
    s.in.resize(n, columns);
    s.out.resize(n, columns);
    s.in_columns.resize(columns);
    s.out_columns.resize(columns);
  }
  const auto& k = coordinates_;
  k.embed_into(w, s.z.data());
  // f, U' = C^T J C U, and with V's block Y' = R J P Y and s' = R (J P s + df/dp): J applied to
  // the columns C U_j, P Y_j and P s, all in one call of the model (one dual-number evaluation
  // for f and all columns; OdeSystem::rhs_and_variational). The parameter column goes last, as
  // variational_rhs wants it.
  // C U and, below, C^T (J C U) by C's nonzero entries alone: C is a basis of W in the state's
  // components (one or two of them per column: 6 of 24 entries for the row setup's anti-phase
  // orbit), and Eigen's small dynamic products of the whole matrices were 8% of the fast preset's
  // instructions on the anti-phase branch (callgrind); scanning C for them at every call, 4%
  // more. Zero terms skipped, in the same order: the sums are exactly the same.
  const double* U = w + across_offset();
  double* in = s.in.data();
  std::fill(in, in + n * a, 0.0);
  for (const Entry& e : breaking_entries_) {
    const double v = e.value;  // a local: the stores below cannot change it
    const double* u = U + e.column;
    double* x = in + e.state;
    for (int j = 0; j < a; ++j) x[j * n] += v * u[j * a];
  }
  for (int j = 0; j < own + with_parameter; ++j)
    k.embed_into(w + r + j * r, s.in.col(a + j).data());
  for (int j = 0; j < columns; ++j) {
    s.in_columns[j] = s.in.col(j).data();
    s.out_columns[j] = s.out.col(j).data();
  }
  const int parameter[] = {parameter_};
  system_.rhs_and_variational(t, s.z.data(), p, s.dz.data(), columns, s.in_columns.data(),
                              s.out_columns.data(),
                              std::span<const int>(parameter, with_parameter));
  for (int i = 0; i < r; ++i) dw[i] = s.dz[k.representative[i]];
  for (int j = 0; j < own + with_parameter; ++j)
    for (int i = 0; i < r; ++i) dw[r + j * r + i] = s.out(k.representative[i], a + j);
  double* dU = dw + across_offset();
  std::fill(dU, dU + a * a, 0.0);
  const double* out = s.out.data();
  for (const Entry& e : breaking_entries_) {
    const double v = e.value;
    const double* y = out + e.state;
    double* u = dU + e.column;
    for (int j = 0; j < a; ++j) u[j * a] += v * y[j * n];
  }
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
  // y, then each column of Y and s: the restricted Jacobian; then U's columns: A.
  for (int j = 0; j < across_offset(); j += r) jac.block(j, j, r, r) = inner;
  for (int j = 0; j < a; ++j) jac.block(across_offset() + j * a, across_offset() + j * a, a, a) = A;
}

void AcrossVariations::variational_rhs(double t, const double* w, const double* p, int columns,
                                       const double* const* S, double* const* out,
                                       std::span<const int> parameters) const {
  if (!parameters.empty())
    throw std::invalid_argument("across variations carry their parameter column in their state");
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
