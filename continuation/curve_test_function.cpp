#include "sympathy/continuation/curve_test_function.hpp"

#include <stdexcept>

namespace sympathy {

Eigen::MatrixXd exterior_square(const Eigen::MatrixXd& b) {
  const int q = static_cast<int>(b.rows());
  if (b.cols() != q) throw std::invalid_argument("exterior_square: expected a square matrix");
  const int size = q * (q - 1) / 2;
  Eigen::MatrixXd c(size, size);
  int row = 0;
  for (int i = 0; i < q; ++i)
    for (int j = i + 1; j < q; ++j, ++row) {
      int col = 0;
      for (int k = 0; k < q; ++k)
        for (int l = k + 1; l < q; ++l, ++col) c(row, col) = b(i, k) * b(j, l) - b(i, l) * b(j, k);
    }
  return c;
}

BorderedSingularity::BorderedSingularity(const Eigen::MatrixXd& a) {
  if (a.rows() != a.cols() || a.rows() == 0)
    throw std::invalid_argument("BorderedSingularity: expected a non-empty square matrix");
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const auto last = a.rows() - 1;
  b_ = svd.matrixU().col(last);
  c_ = svd.matrixV().col(last);
}

BorderedSingularity::Value BorderedSingularity::value(const Eigen::MatrixXd& a) const {
  const auto q = a.rows();
  if (q != b_.size() || a.cols() != q)
    throw std::invalid_argument("BorderedSingularity: a matrix of another size than the borders'");
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(q + 1, q + 1);
  m.topLeftCorner(q, q) = a;
  m.topRightCorner(q, 1) = b_;
  m.bottomLeftCorner(1, q) = c_.transpose();
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(m);
  Eigen::VectorXd e = Eigen::VectorXd::Zero(q + 1);
  e[q] = 1.0;
  const Eigen::VectorXd right = lu.solve(e);
  // The transposed system [A^T c; b^T 0] [w; g] = [0; 1] has the same g.
  const Eigen::VectorXd left = lu.transpose().solve(e);
  Value out;
  out.g = right[q];
  out.v = right.head(q);
  out.w = left.head(q);
  return out;
}

void BorderedSingularity::update(const Eigen::MatrixXd& a) {
  const Value now = value(a);
  if (!(now.v.allFinite() && now.w.allFinite()) || now.v.norm() == 0.0 || now.w.norm() == 0.0)
    return;
  // v and w point along c and b (c^T v = b^T w = 1): the new borders keep their orientation,
  // and with it the sign of g.
  c_ = now.v.normalized();
  b_ = now.w.normalized();
}

}  // namespace sympathy
