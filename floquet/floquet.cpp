#include "floquet/floquet.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

#include "floquet/periodic_schur.hpp"

namespace sympathy {

std::string to_string(Stability s) {
  switch (s) {
    case Stability::Stable:
      return "stable";
    case Stability::Unstable:
      return "unstable";
    case Stability::Marginal:
      return "marginal";
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

}  // namespace

FloquetAnalysis analyze_floquet(const std::vector<Eigen::MatrixXd>& segments,
                                const Eigen::VectorXd& flow_direction,
                                const Eigen::MatrixXd& family, const FloquetOptions& options) {
  if (segments.empty()) throw std::invalid_argument("analyze_floquet: no segment matrices");
  const int n = static_cast<int>(segments.front().rows());

  // The product is formed for eigenvectors only (to find the trivial and structural
  // multipliers); with one segment it is the monodromy and its eigenvalues are the multipliers.
  Eigen::MatrixXd monodromy = segments.front();
  for (std::size_t k = 1; k < segments.size(); ++k) monodromy = segments[k] * monodromy;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(monodromy,
                                          flow_direction.size() > 0 || family.cols() > 0);

  FloquetAnalysis a;
  std::vector<std::complex<double>> values;
  std::vector<double> logs;
  if (segments.size() == 1) {
    for (int i = 0; i < n; ++i) {
      values.push_back(eig.eigenvalues()[i]);
      logs.push_back(std::log(std::abs(values.back())));
    }
  } else {
    const auto p = product_eigenvalues(segments);
    values = p.values;
    logs = p.log_moduli;
  }
  for (int i = 0; i < n; ++i) a.multipliers.push_back({values[i], logs[i]});

  // The trivial multiplier is the one whose eigenvector is f, the structural ones those whose
  // eigenvectors lie along the family's directions: identified by eigenvectors, not by being
  // nearest to 1. Eigenvectors come from the formed product, matched to the multipliers by
  // value (accurate for moduli near 1).
  std::vector<bool> taken(n, false);
  const bool autonomous = flow_direction.size() == n && flow_direction.norm() > 0.0;
  if (autonomous || family.cols() > 0) {
    std::vector<Eigen::VectorXcd> vectors;
    for (int i = 0; i < n; ++i) {
      int nearest = 0;
      for (int j = 1; j < n; ++j)
        if (std::abs(eig.eigenvalues()[j] - values[i]) <
            std::abs(eig.eigenvalues()[nearest] - values[i]))
          nearest = j;
      vectors.push_back(eig.eigenvectors().col(nearest).normalized());
    }
    if (autonomous) {
      const auto [index, alignment] = aligned(values, vectors, flow_direction, taken);
      a.trivial = index;
      a.trivial_alignment = alignment;
      taken[index] = true;
      a.multipliers[index].trivial = true;
    }
    for (int k = 0; k < family.cols() && k + 1 < n; ++k) {
      // A family direction from a null vector of the shooting equations mixes in f (the phase
      // condition fixes only the mixture): take f out before aligning.
      Eigen::VectorXd d = family.col(k);
      if (autonomous) {
        const Eigen::VectorXd f = flow_direction.normalized();
        d -= f.dot(d) * f;
      }
      const int index = aligned(values, vectors, d, taken).first;
      taken[index] = true;
      a.multipliers[index].structural = true;
      ++a.structural;
    }
  }

  // Order by decreasing modulus, keeping track of the trivial one.
  std::stable_sort(a.multipliers.begin(), a.multipliers.end(),
                   [](const auto& x, const auto& y) { return x.log_modulus > y.log_modulus; });
  // Conjugate pairs have equal moduli up to rounding: put the positive argument first, so that
  // the order does not depend on the last bit.
  for (int i = 0; i + 1 < n; ++i) {
    auto& p = a.multipliers[i];
    auto& q = a.multipliers[i + 1];
    if (std::abs(p.value - std::conj(q.value)) <= 1e-9 * std::abs(p.value) &&
        p.value.imag() < q.value.imag())
      std::swap(p, q);
  }
  a.trivial = -1;
  for (int i = 0; i < n; ++i)
    if (a.multipliers[i].trivial) a.trivial = i;
  if (a.trivial >= 0) a.trivial_error = std::abs(a.multipliers[a.trivial].value - 1.0);

  const double tol = options.stability_tolerance;
  a.max_modulus = 0.0;
  for (const auto& m : a.multipliers) {
    if (m.trivial || m.structural) continue;
    a.max_modulus = std::max(a.max_modulus, m.modulus());
    if (m.modulus() > 1.0 + tol) ++a.unstable_count;
  }
  a.stability = a.max_modulus < 1.0 - tol   ? Stability::Stable
                : a.max_modulus > 1.0 + tol ? Stability::Unstable
                                            : Stability::Marginal;
  return a;
}

}  // namespace sympathy
