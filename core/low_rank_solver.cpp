#include "sympathy/core/low_rank_solver.hpp"

#include <klu.h>

#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>

namespace sympathy {

namespace {

// How far KLU's condition estimate (min |U_ii| / max |U_ii|) may fall in a refactorization
// before the matrix is factored afresh with pivoting.
constexpr double kRefactorLoss = 0.1;

}  // namespace

// KLU's objects, freed with it.
struct LowRankSolver::Klu {
  klu_common common;
  klu_symbolic* symbolic = nullptr;
  klu_numeric* numeric = nullptr;
  Klu() { klu_defaults(&common); }
  Klu(const Klu&) = delete;
  Klu& operator=(const Klu&) = delete;
  ~Klu() {
    if (numeric) klu_free_numeric(&numeric, &common);
    if (symbolic) klu_free_symbolic(&symbolic, &common);
  }
};

LowRankSolver::LowRankSolver(const LowRankJacobian& s)
    : n_(s.dimension), rank_(s.rank()), klu_(std::make_unique<Klu>()) {
  if (static_cast<int>(s.column_starts.size()) != n_ + 1 ||
      static_cast<int>(s.values.size()) != s.nonzeros() || s.U.rows() != n_ || s.W.rows() != n_ ||
      s.W.cols() != rank_)
    throw std::invalid_argument("low-rank solver: inconsistent Jacobian structure");
  // The pattern of I - gamma S: each column of S with its diagonal entry merged in.
  column_starts_.assign(n_ + 1, 0);
  from_s_.resize(s.nonzeros());
  diagonal_.resize(n_);
  for (int j = 0; j < n_; ++j) {
    bool diagonal_placed = false;
    for (int k = s.column_starts[j]; k < s.column_starts[j + 1]; ++k) {
      const int i = s.row_indices[k];
      if (!diagonal_placed && i > j) {
        diagonal_[j] = static_cast<int>(row_indices_.size());
        row_indices_.push_back(j);
        diagonal_placed = true;
      }
      from_s_[k] = static_cast<int>(row_indices_.size());
      if (i == j) {
        diagonal_[j] = from_s_[k];
        diagonal_placed = true;
      }
      row_indices_.push_back(i);
    }
    if (!diagonal_placed) {
      diagonal_[j] = static_cast<int>(row_indices_.size());
      row_indices_.push_back(j);
    }
    column_starts_[j + 1] = static_cast<int>(row_indices_.size());
  }
  values_.assign(row_indices_.size(), 0.0);
  klu_->symbolic = klu_analyze(n_, column_starts_.data(), row_indices_.data(), &klu_->common);
  if (!klu_->symbolic)
    throw std::runtime_error("KLU: klu_analyze failed (status " +
                             std::to_string(klu_->common.status) + ")");
  Z_.resize(n_, rank_);
  W_.resize(n_, rank_);
  small_.resize(rank_);
  projected_.resize(rank_);
  capacitance_.resize(rank_, rank_);
  capacitance_inverse_.resize(rank_, rank_);
}

LowRankSolver::~LowRankSolver() = default;

bool LowRankSolver::factor(const LowRankJacobian& jac, double gamma) {
  if (jac.dimension != n_ || jac.rank() != rank_ ||
      jac.nonzeros() != static_cast<int>(from_s_.size()) ||
      static_cast<int>(jac.values.size()) != jac.nonzeros() || jac.W.cols() != rank_)
    throw std::invalid_argument("low-rank solver: Jacobian does not match the analyzed structure");
  factored_ = false;
  std::fill(values_.begin(), values_.end(), 0.0);
  for (std::size_t k = 0; k < from_s_.size(); ++k) values_[from_s_[k]] = -gamma * jac.values[k];
  for (int j = 0; j < n_; ++j) values_[diagonal_[j]] += 1.0;
  for (double v : values_)
    if (!std::isfinite(v)) return false;

  // Refactor in the pivot order of the last factorization with pivoting (no allocation, no
  // pivot search: CVODES sets up every few steps where steep zones change the step size), unless
  // KLU's condition estimate fell by more than kRefactorLoss from that factorization's; then
  // factor afresh with partial pivoting.
  auto& klu = *klu_;
  bool done = false;
  if (klu.numeric && klu_refactor(column_starts_.data(), row_indices_.data(), values_.data(),
                                  klu.symbolic, klu.numeric, &klu.common)) {
    done = klu_rcond(klu.symbolic, klu.numeric, &klu.common) &&
           klu.common.rcond >= kRefactorLoss * pivoted_rcond_;
    if (done) ++refactorizations_;
  }
  if (!done) {
    if (klu.numeric) klu_free_numeric(&klu.numeric, &klu.common);
    klu.numeric = klu_factor(column_starts_.data(), row_indices_.data(), values_.data(),
                             klu.symbolic, &klu.common);
    ++factorizations_;
    if (!klu.numeric || klu.common.status != KLU_OK) return false;
    if (!klu_rcond(klu.symbolic, klu.numeric, &klu.common)) return false;
    pivoted_rcond_ = klu.common.rcond;
  }
  if (!(klu.common.rcond > std::numeric_limits<double>::epsilon())) return false;

  if (rank_ > 0) {
    Z_ = jac.U;
    if (!klu_solve(klu.symbolic, klu.numeric, n_, rank_, Z_.data(), &klu.common)) return false;
    W_ = jac.W;
    // Into members sized once: CVODES sets up often, and the sizes never change.
    capacitance_.noalias() = -gamma * (W_.transpose() * Z_);
    capacitance_.diagonal().array() += 1.0;
    capacitance_lu_.compute(capacitance_);
    if (!(capacitance_lu_.rcond() > std::numeric_limits<double>::epsilon())) return false;
    capacitance_inverse_ = capacitance_lu_.inverse();
    Z_ *= gamma;  // solve() needs gamma Z
    if (!Z_.allFinite() || !capacitance_inverse_.allFinite()) return false;
  }
  factored_ = true;
  return true;
}

void LowRankSolver::solve(double* x) {
  if (!factored_) throw std::logic_error("low-rank solver: solve without a factorization");
  auto& klu = *klu_;
  klu_solve(klu.symbolic, klu.numeric, n_, 1, x, &klu.common);
  if (rank_ == 0) return;
  Eigen::Map<Eigen::VectorXd> y(x, n_);
  projected_.noalias() = W_.transpose() * y;  // no temporaries: solve() runs per Newton iteration
  small_.noalias() = capacitance_inverse_ * projected_;
  y.noalias() += Z_ * small_;
}

}  // namespace sympathy
