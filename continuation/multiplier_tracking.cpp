#include "sympathy/continuation/multiplier_tracking.hpp"

#include <algorithm>
#include <limits>

#include "sympathy/core/assignment.hpp"

namespace sympathy {

std::vector<Multiplier> nontrivial(const FloquetAnalysis& f) {
  std::vector<Multiplier> v;
  for (const auto& m : f.multipliers)
    if (!m.trivial && !m.structural) v.push_back(m);
  return v;
}

namespace {

// Whether x and y may be one multiplier followed: not where one keeps the subspace's symmetry and
// the other breaks it. Those are eigenvalues of different blocks of the monodromy, and pass
// through each other without exchanging: on the row setup's anti-phase k-branch the breaking
// multiplier rising from 0.92 to 0.94 passes the keeping 0.9228 at k = 47.0, next to the BP,
// where pairing by distance alone was doubtful and three steps were retried shorter.
bool may_exchange(const Multiplier& x, const Multiplier& y) {
  return x.symmetry == SymmetryKind::Unlabelled || y.symmetry == SymmetryKind::Unlabelled ||
         x.symmetry == y.symmetry;
}

// Pairs (a_i, b_j) with the least total squared distance (the longer list's extra ones unpaired),
// among those that may exchange before any that may not.
std::vector<std::pair<Multiplier, Multiplier>> match(const std::vector<Multiplier>& a,
                                                     const std::vector<Multiplier>& b) {
  const int n = static_cast<int>(std::max(a.size(), b.size()));
  Eigen::MatrixXd cost = Eigen::MatrixXd::Zero(n, n);  // a row or column past the end: unpaired
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j) cost(i, j) = std::norm(a[i].value - b[j].value);
  // More than any assignment's whole cost by distance: one pair fewer across symmetries wins.
  const double apart = 1.0 + 2.0 * cost.sum();
  for (std::size_t i = 0; i < a.size(); ++i)
    for (std::size_t j = 0; j < b.size(); ++j)
      if (!may_exchange(a[i], b[j])) cost(i, j) += apart;
  const std::vector<int> column = least_cost_assignment(cost);
  std::vector<std::pair<Multiplier, Multiplier>> pairs;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (column[i] < static_cast<int>(b.size())) pairs.emplace_back(a[i], b[column[i]]);
  return pairs;
}

TrackedMultipliers follow(const std::vector<Multiplier>& a, const std::vector<Multiplier>* before,
                          double ratio, const std::vector<Multiplier>& b) {
  std::vector<Multiplier> predicted = a;
  if (before && before->size() == a.size() && ratio > 0.0)
    for (const auto& [x, y] : match(*before, a))
      for (std::size_t i = 0; i < a.size(); ++i)
        if (a[i].value == y.value) predicted[i].value = y.value + ratio * (y.value - x.value);
  struct Link {
    Multiplier origin, predicted, match;
  };
  std::vector<Link> links;
  for (const auto& [p, y] : match(predicted, b)) {
    Multiplier origin = p;  // back from the prediction to a's own multiplier
    for (std::size_t i = 0; i < predicted.size(); ++i)
      if (predicted[i].value == p.value) origin = a[i];
    links.push_back({origin, p, y});
  }
  TrackedMultipliers t;
  for (const auto& l : links) {
    // The gap to the nearest other match whose swap with this one could change a modulus: not
    // this one's complex conjugate, nor the match of its origin's conjugate (where two real
    // multipliers collide into a pair, or a pair splits, the two have one modulus either way),
    // nor one of the other symmetry (they cannot swap).
    double gap = std::numeric_limits<double>::infinity();
    for (const auto& o : links) {
      const bool same = o.match.value == l.match.value;
      const bool conjugates =
          o.match.value == std::conj(l.match.value) || o.origin.value == std::conj(l.origin.value);
      if (!same && !conjugates && may_exchange(o.match, l.match))
        gap = std::min(gap, std::abs(o.match.value - l.match.value));
    }
    const double from_circle =
        std::min(std::abs(l.origin.modulus() - 1.0), std::abs(l.match.modulus() - 1.0));
    if (gap > 0.01 && from_circle < 0.1)
      t.ambiguity = std::max(t.ambiguity, std::abs(l.predicted.value - l.match.value) / gap);
    t.pairs.emplace_back(l.origin, l.match);
  }
  return t;
}

}  // namespace

TrackedMultipliers track(const ContinuationPoint* before, const ContinuationPoint& a,
                         const ContinuationPoint& b) {
  const auto na = nontrivial(a.orbit.floquet), nb = nontrivial(b.orbit.floquet);
  const double ratio = a.step > 0.0 ? b.step / a.step : 0.0;
  if (before) {
    const auto nbefore = nontrivial(before->orbit.floquet);
    return follow(na, &nbefore, ratio, nb);
  }
  return follow(na, nullptr, 0.0, nb);
}

}  // namespace sympathy
