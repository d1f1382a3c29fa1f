#include "sympathy/floquet/floquet.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "summary.hpp"
#include "sympathy/core/assignment.hpp"
#include "sympathy/floquet/periodic_schur.hpp"

namespace sympathy {

std::string to_string(Stability s) {
  switch (s) {
    case Stability::Stable:
      return "stable";
    case Stability::Unstable:
      return "unstable";
    case Stability::Marginal:
      return "marginal";
    case Stability::Unresolved:
      return "unresolved";
  }
  return "?";
}

namespace {

// The multiplier whose eigenvector lies along `direction`, among those not excluded. Within a
// cluster of (nearly) equal multipliers single eigenvectors are arbitrary, so first the cluster
// whose eigenvectors' span holds the direction best (all its members count, taken ones too: a
// family's multiplier shares its eigenspace with the trivial one), then the free member whose
// own vector does. Returns the index and the member's alignment |cos|.
std::pair<int, double> aligned(const std::vector<std::complex<double>>& values,
                               const std::vector<Eigen::VectorXcd>& vectors,
                               const Eigen::VectorXd& direction,
                               const std::vector<bool>& excluded) {
  const int n = static_cast<int>(values.size());
  const Eigen::VectorXcd d = direction.cast<std::complex<double>>().normalized();
  int best = -1;
  double best_span = -1.0, best_own = -1.0;
  for (int i = 0; i < n; ++i) {
    if (excluded[i]) continue;
    std::vector<int> cluster;
    for (int j = 0; j < n; ++j)
      if (std::abs(values[j] - values[i]) <= 1e-6 * std::max(1.0, std::abs(values[i])))
        cluster.push_back(j);
    Eigen::MatrixXcd span(n, cluster.size());
    for (std::size_t k = 0; k < cluster.size(); ++k) span.col(k) = vectors[cluster[k]];
    const Eigen::HouseholderQR<Eigen::MatrixXcd> qr(span);
    const Eigen::MatrixXcd q =
        qr.householderQ() * Eigen::MatrixXcd::Identity(n, static_cast<int>(cluster.size()));
    const double in_span = (q.adjoint() * d).norm();
    const double own = std::abs(vectors[i].dot(d));
    if (in_span > best_span + 1e-12 || (std::abs(in_span - best_span) <= 1e-12 && own > best_own)) {
      best_span = std::max(best_span, in_span);
      best = i;
      best_own = own;
    }
  }
  return {best, best_own};
}

// Eigenvalues of the product of `factors` (one factor: its own eigenvalues). Where periodic QR
// does not converge (seen on a 2x2 window of Lorenz's orbits near the homoclinic one, with four
// segments), the eigenvalues of the formed product: less accurate for multipliers beyond
// 1e+-16 of each other, but a result, where the exception ended the whole branch.
ProductEigenvalues eigenvalues_of_product(const std::vector<Eigen::MatrixXd>& factors) {
  std::vector<Eigen::MatrixXd> formed;
  if (factors.size() > 1) {
    try {
      return product_eigenvalues(factors);
    } catch (const std::runtime_error&) {
      formed.push_back(monodromy(factors));
    }
  }
  ProductEigenvalues p;
  const Eigen::VectorXcd values = (formed.empty() ? factors : formed).front().eigenvalues();
  for (int i = 0; i < values.size(); ++i) {
    p.values.push_back(values[i]);
    p.log_moduli.push_back(std::log(std::abs(values[i])));
  }
  return p;
}

// A full orthonormal basis whose first columns span those of `a` (n x d, full column rank).
Eigen::MatrixXd completed_basis(const Eigen::MatrixXd& a) {
  return Eigen::HouseholderQR<Eigen::MatrixXd>(a).householderQ() *
         Eigen::MatrixXd::Identity(a.rows(), a.rows());
}

// The segment matrices acting on the quotient by a subspace V that they carry into itself (f
// and the family's directions): in bases U_j = [V_j Q_j] at the segment ends, V_{j+1} the image
// of V_j and back to V_0 at the end of the period, each segment matrix is block upper
// triangular, and its lower diagonal block is the quotient's.
std::vector<Eigen::MatrixXd> quotient_segments(const std::vector<Eigen::MatrixXd>& segments,
                                               const Eigen::MatrixXd& v0) {
  const int n = static_cast<int>(v0.rows()), d = static_cast<int>(v0.cols());
  const Eigen::MatrixXd u0 = completed_basis(v0);
  std::vector<Eigen::MatrixXd> quotient;
  Eigen::MatrixXd u = u0;
  for (std::size_t j = 0; j < segments.size(); ++j) {
    const Eigen::MatrixXd next =
        j + 1 < segments.size() ? completed_basis(segments[j] * u.leftCols(d)) : u0;
    quotient.push_back(
        (next.rightCols(n - d).transpose() * segments[j] * u.rightCols(n - d)).eval());
    u = next;
  }
  return quotient;
}

}  // namespace

Eigen::MatrixXd monodromy(const std::vector<Eigen::MatrixXd>& segments) {
  Eigen::MatrixXd m = segments.front();
  for (std::size_t k = 1; k < segments.size(); ++k) m = segments[k] * m;
  return m;
}

void order_and_summarize(FloquetAnalysis& a, const FloquetOptions& options) {
  // Order by decreasing modulus, keeping track of the trivial one.
  std::stable_sort(a.multipliers.begin(), a.multipliers.end(),
                   [](const auto& x, const auto& y) { return x.log_modulus > y.log_modulus; });
  // Conjugate pairs have equal moduli up to rounding: put the positive argument first, so that
  // the order does not depend on the last bit.
  for (int i = 0; i + 1 < static_cast<int>(a.multipliers.size()); ++i) {
    auto& p = a.multipliers[i];
    auto& q = a.multipliers[i + 1];
    if (std::abs(p.value - std::conj(q.value)) <= 1e-9 * std::abs(p.value) &&
        p.value.imag() < q.value.imag())
      std::swap(p, q);
  }
  summarize(a, options);
}

void summarize(FloquetAnalysis& a, const FloquetOptions& options) {
  a.trivial = -1;
  for (int i = 0; i < static_cast<int>(a.multipliers.size()); ++i)
    if (a.multipliers[i].trivial) a.trivial = i;
  if (a.trivial >= 0) a.trivial_error = std::abs(a.multipliers[a.trivial].value - 1.0);
  // A trivial multiplier out of the range of double (|M| past 1e308 near a homoclinic orbit:
  // its value inf times a phase, NaN) resolves nothing: its error is infinite, never NaN, which
  // every comparison below would take for a small one (such orbits of AUTO's ab at T 325 came
  // out "stable").
  if (std::isnan(a.trivial_error)) a.trivial_error = std::numeric_limits<double>::infinity();

  const double tol = options.stability_tolerance;
  a.max_modulus = 0.0;
  a.unstable_count = 0;
  for (const auto& m : a.multipliers) {
    if (m.trivial || m.structural) continue;
    a.max_modulus = std::max(a.max_modulus, m.modulus());
    if (m.modulus() > 1.0 + tol) ++a.unstable_count;
  }
  // The verdict holds within the multipliers' error, of which the trivial one's is the measure.
  const double margin = std::max(tol, a.trivial_error);
  a.stability = a.max_modulus < 1.0 - margin   ? Stability::Stable
                : a.max_modulus > 1.0 + margin ? Stability::Unstable
                : margin > tol                 ? Stability::Unresolved
                                               : Stability::Marginal;
}

FloquetAnalysis analyze_floquet(const std::vector<Eigen::MatrixXd>& segments,
                                const Eigen::VectorXd& flow_direction,
                                const Eigen::MatrixXd& family, const FloquetOptions& options) {
  if (segments.empty()) throw std::invalid_argument("analyze_floquet: no segment matrices");
  const int n = static_cast<int>(segments.front().rows());
  FloquetAnalysis a;

  // The known invariant subspace V: f and the family's directions (f taken out of each: a null
  // vector of the shooting equations mixes it in; directions already spanned dropped).
  const bool autonomous = flow_direction.size() == n && flow_direction.norm() > 0.0;
  std::vector<Eigen::VectorXd> known;
  if (autonomous) known.push_back(flow_direction.normalized());
  for (int k = 0; k < family.cols() && static_cast<int>(known.size()) < n; ++k) {
    Eigen::VectorXd v = family.col(k);
    const double size = v.norm();
    for (const auto& q : known) v -= q.dot(v) * q;
    if (v.norm() > 1e-6 * size) known.push_back(v.normalized());
  }
  const int d = static_cast<int>(known.size());
  if (d == 0) {
    const auto all = eigenvalues_of_product(segments);
    for (int i = 0; i < n; ++i) a.multipliers.push_back({all.values[i], all.log_moduli[i]});
  } else {
    // Eigenvectors (to tell the trivial multiplier) come from the formed product; with one
    // segment its eigenvalues are the multipliers too, so one decomposition serves both.
    const Eigen::MatrixXd product = monodromy(segments);
    const Eigen::EigenSolver<Eigen::MatrixXd> eig(product);
    ProductEigenvalues all;
    if (segments.size() > 1) {
      all = eigenvalues_of_product(segments);
    } else {
      for (int i = 0; i < n; ++i) {
        all.values.push_back(eig.eigenvalues()[i]);
        all.log_moduli.push_back(std::log(std::abs(eig.eigenvalues()[i])));
      }
    }
    // The other multipliers are the eigenvalues on the quotient by V: they never share a cluster
    // with the multipliers at 1 that f and the family force, so one crossing 1 at a branch point
    // is not mistaken for those (nor its value for theirs).
    Eigen::MatrixXd v0(n, d);
    for (int k = 0; k < d; ++k) v0.col(k) = known[k];
    const auto others =
        d < n ? eigenvalues_of_product(quotient_segments(segments, v0)) : ProductEigenvalues{};
    // The d of all multipliers that the others do not match (least total squared distance; d
    // empty rows take the rest) are the trivial and structural ones.
    Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(n, n);
    for (int i = 0; i < n - d; ++i)
      for (int j = 0; j < n; ++j) cost(i, j) = std::norm(others.values[i] - all.values[j]);
    const std::vector<int> column = least_cost_assignment(cost);
    std::vector<bool> used(n, false);
    for (int i = 0; i < n - d; ++i) used[column[i]] = true;
    // Among those, the trivial one by its eigenvector.
    std::vector<Eigen::VectorXcd> vectors;
    for (int i = 0; i < n; ++i) {
      int nearest = 0;
      for (int j = 1; j < n; ++j)
        if (std::abs(eig.eigenvalues()[j] - all.values[i]) <
            std::abs(eig.eigenvalues()[nearest] - all.values[i]))
          nearest = j;
      vectors.push_back(eig.eigenvectors().col(nearest).normalized());
    }
    int trivial = -1;
    if (autonomous) {
      const auto [index, alignment] = aligned(all.values, vectors, flow_direction, used);
      trivial = index;
      a.trivial_alignment = alignment;
    }
    // With a family, its multipliers and the trivial one are a defective cluster at 1 (moving
    // along the family changes the period: M v = v + alpha f), whose eigenvalues split like the
    // square root of the monodromy's error (1e-15 puts them 3e-8 apart). Their values then come
    // from the compression of the monodromy onto V (f first), which is triangular with them on
    // its diagonal and first-order accurate, as an accuracy figure must be. So does the trivial
    // one's always: at a generic fold of cycles it is in such a cluster with the multiplier
    // passing through 1 (the period changes along the branch), and its eigenvalue there was
    // 1e-5 to 1e-3 from 1 on AUTO's demos with the orbit right to 1e-10; away from clusters
    // f^T M f / f^T f and the eigenvalue agree to the monodromy's error.
    const Eigen::MatrixXd compressed = v0.transpose() * product * v0;
    int next_structural = autonomous ? 1 : 0;  // V's columns: f (if autonomous), then the family
    for (int i = 0; i < n; ++i) {
      if (used[i]) continue;
      Multiplier mu{all.values[i], all.log_moduli[i]};
      mu.trivial = i == trivial;
      mu.structural = !mu.trivial;
      if (d > 1 || mu.trivial) {
        const int k = std::min(mu.trivial ? 0 : next_structural++, d - 1);
        mu.value = compressed(k, k);
        mu.log_modulus = std::log(std::abs(mu.value));
      }
      a.structural += mu.structural ? 1 : 0;
      a.multipliers.push_back(mu);
    }
    for (int i = 0; i < n - d; ++i)
      a.multipliers.push_back({others.values[i], others.log_moduli[i]});
  }

  order_and_summarize(a, options);
  return a;
}

}  // namespace sympathy
