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

FloquetAnalysis analyze_floquet(const std::vector<Eigen::MatrixXd>& segments,
                                const Eigen::VectorXd& flow_direction, int structural,
                                const FloquetOptions& options) {
  if (segments.empty()) throw std::invalid_argument("analyze_floquet: no segment matrices");
  const int n = static_cast<int>(segments.front().rows());

  // The product is formed for eigenvectors only (to find the trivial multiplier); with one
  // segment it is the monodromy and its eigenvalues are the multipliers.
  Eigen::MatrixXd monodromy = segments.front();
  for (std::size_t k = 1; k < segments.size(); ++k) monodromy = segments[k] * monodromy;
  Eigen::EigenSolver<Eigen::MatrixXd> eig(monodromy, flow_direction.size() > 0);

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

  if (flow_direction.size() == n && flow_direction.norm() > 0.0) {
    // The trivial multiplier is the one whose eigenvector is f. Eigenvectors come from the
    // formed product, matched to the multipliers by value (accurate for moduli near 1). Within
    // a cluster of (nearly) equal multipliers, as on a family of orbits, single eigenvectors are
    // arbitrary, so first choose the cluster whose eigenvectors' span holds f best, then the
    // member whose own eigenvector does.
    const Eigen::VectorXcd f = flow_direction.cast<std::complex<double>>().normalized();
    std::vector<Eigen::VectorXcd> vectors;
    for (int i = 0; i < n; ++i) {
      int nearest = 0;
      for (int j = 1; j < n; ++j)
        if (std::abs(eig.eigenvalues()[j] - values[i]) <
            std::abs(eig.eigenvalues()[nearest] - values[i]))
          nearest = j;
      vectors.push_back(eig.eigenvectors().col(nearest).normalized());
    }
    double best_span = -1.0;
    for (int i = 0; i < n; ++i) {
      std::vector<int> cluster;
      for (int j = 0; j < n; ++j)
        if (std::abs(values[j] - values[i]) <= 1e-6 * std::max(1.0, std::abs(values[i])))
          cluster.push_back(j);
      Eigen::MatrixXcd span(n, cluster.size());
      for (std::size_t k = 0; k < cluster.size(); ++k) span.col(k) = vectors[cluster[k]];
      const Eigen::HouseholderQR<Eigen::MatrixXcd> qr(span);
      const Eigen::MatrixXcd q =
          qr.householderQ() * Eigen::MatrixXcd::Identity(n, static_cast<int>(cluster.size()));
      const double in_span = (q.adjoint() * f).norm();
      const double own = std::abs(vectors[i].dot(f));
      // Prefer the better span; among members of one cluster (equal spans), the better vector.
      if (in_span > best_span + 1e-12 ||
          (std::abs(in_span - best_span) <= 1e-12 && own > a.trivial_alignment)) {
        best_span = std::max(best_span, in_span);
        a.trivial = i;
        a.trivial_alignment = own;
      }
    }
  }

  // Order by decreasing modulus, keeping track of the trivial one.
  if (a.trivial >= 0) a.multipliers[a.trivial].trivial = true;
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

  // Structural multipliers: the nontrivial ones nearest to 1.
  std::vector<int> order;
  for (int i = 0; i < n; ++i)
    if (i != a.trivial) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](int x, int y) {
    return std::abs(a.multipliers[x].value - 1.0) < std::abs(a.multipliers[y].value - 1.0);
  });
  a.structural = std::min<int>(structural, static_cast<int>(order.size()));
  for (int k = 0; k < a.structural; ++k) a.multipliers[order[k]].structural = true;

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
