#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "summary.hpp"
#include "sympathy/core/assignment.hpp"
#include "sympathy/floquet/floquet.hpp"
#include "sympathy/floquet/periodic_schur.hpp"

namespace sympathy {

std::string to_string(SymmetryKind k) {
  switch (k) {
    case SymmetryKind::Unlabelled:
      return "";
    case SymmetryKind::Keeping:
      return "keeps";
    case SymmetryKind::Breaking:
      return "breaks";
  }
  return "?";
}

void label_symmetry(FloquetAnalysis& a, const std::vector<Eigen::MatrixXd>& segments,
                    const Eigen::MatrixXd& inside, const Eigen::MatrixXd& across) {
  const int n = static_cast<int>(a.multipliers.size());
  if (segments.empty() || inside.cols() == 0 || across.cols() == 0 ||
      inside.cols() + across.cols() != n)
    return;
  std::vector<Eigen::MatrixXd> kept, broken;
  double leak = 0.0;
  for (const auto& phi : segments) {
    const double size = std::max(phi.norm(), 1e-300);
    leak = std::max(leak, (across.transpose() * phi * inside).norm() / size);
    kept.push_back(inside.transpose() * phi * inside);
    broken.push_back(across.transpose() * phi * across);
  }
  a.symmetry_defect = leak;
  if (leak > 1e-6) return;
  const ProductEigenvalues k = product_eigenvalues(kept), b = product_eigenvalues(broken);
  std::vector<std::complex<double>> blocks = k.values;
  blocks.insert(blocks.end(), b.values.begin(), b.values.end());
  const int keeping = static_cast<int>(k.values.size());
  // The trivial multiplier's eigenvector f lies in the subspace (the orbit does): it keeps the
  // symmetry, whatever other multiplier lies as near 1 (a family's, cross4's in-in orbit).
  constexpr double kForbidden = 1e30;
  Eigen::MatrixXd cost(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      cost(i, j) = i == a.trivial && j >= keeping ? kForbidden
                                                  : std::norm(a.multipliers[i].value - blocks[j]);
  const std::vector<int> column = least_cost_assignment(cost);
  for (int i = 0; i < n; ++i)
    a.multipliers[i].symmetry =
        column[i] < keeping ? SymmetryKind::Keeping : SymmetryKind::Breaking;
}

FloquetAnalysis repeat_breaking(FloquetAnalysis a, int copies, const FloquetOptions& options) {
  if (copies < 1) throw std::invalid_argument("repeat_breaking: copies must be at least 1");
  // Each run of breaking multipliers of one modulus (a conjugate pair, or a real one) repeated
  // in place: the order by modulus stays, and pairs stay together.
  std::vector<Multiplier> all;
  const auto& m = a.multipliers;
  for (std::size_t i = 0; i < m.size();) {
    std::size_t end = i + 1;
    if (m[i].symmetry == SymmetryKind::Breaking)
      while (end < m.size() && m[end].symmetry == SymmetryKind::Breaking &&
             std::abs(m[end].log_modulus - m[i].log_modulus) <= 1e-9)
        ++end;
    const int times = m[i].symmetry == SymmetryKind::Breaking ? copies : 1;
    for (int c = 0; c < times; ++c) all.insert(all.end(), m.begin() + i, m.begin() + end);
    i = end;
  }
  a.multipliers = std::move(all);
  summarize(a, options);
  return a;
}

}  // namespace sympathy
