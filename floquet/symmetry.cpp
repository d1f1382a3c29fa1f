#include <algorithm>

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

}  // namespace sympathy
