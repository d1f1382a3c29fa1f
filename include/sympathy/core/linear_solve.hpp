// Solving the bordered linear systems of shooting Newton steps.
//
// Columns, then rows, are scaled to unit norm first, so that mixed units (metres of platform
// travel next to radians and seconds) do not pass for rank deficiency. A sparse system is factored
// by UMFPACK; a small one, or one UMFPACK finds (nearly) singular, by a singular value
// decomposition, which gives the rank and the minimum-norm solution. A singular system is not an
// error: on a continuum of periodic orbits the Newton step is the minimum-norm one, and the rank
// deficiency is the dimension of the continuum.
#pragma once

#include <Eigen/Dense>
#include <Eigen/SparseCore>

namespace sympathy {

struct LinearSolution {
  Eigen::VectorXd x;
  int rank_deficiency = 0;
  bool sparse = false;  // solved by the sparse LU
};

struct LinearSolveOptions {
  bool prefer_sparse = false;
  // Relative size (of the column-scaled matrix) below which a direction counts as singular.
  double rank_tolerance = 1e-6;
  // UMFPACK's reciprocal condition estimate below which the dense rank-revealing solve is used.
  double sparse_rcond_limit = 1e-9;
};

// Dimension of the null space of the column-scaled matrix (see rank_tolerance).
int rank_deficiency(const Eigen::SparseMatrix<double>& a, double rank_tolerance = 1e-6);
// Its `dimension` right null vectors (least singular), in the unscaled variables, as columns.
Eigen::MatrixXd null_vectors(const Eigen::SparseMatrix<double>& a, int dimension);

LinearSolution solve_linear(const Eigen::SparseMatrix<double>& a, const Eigen::VectorXd& b,
                            const LinearSolveOptions& options = {});

}  // namespace sympathy
