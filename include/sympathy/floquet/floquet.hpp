// Floquet multipliers of a periodic orbit and what they say.
//
// From one monodromy matrix (single shooting) the multipliers are its eigenvalues. From the
// segment matrices of multiple shooting they come from a periodic Schur decomposition of the
// segments (floquet/periodic_schur.hpp), never from their product, which loses small
// multipliers to rounding. The trivial multiplier of an autonomous system (eigenvector along
// the vector field f) is identified by that eigenvector, not by being nearest to 1, and its
// distance from 1 is the orbit's accuracy figure. Multipliers at 1 that a continuum of orbits
// forces (a family, found by the shooting Newton as a rank deficiency) are marked structural.
// All other multipliers are the eigenvalues on the quotient by the span of f and the family's
// directions (an invariant subspace): one crossing 1 among the trivial and structural ones, as
// at a branch point on a family, keeps its own value and is never taken for them.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/option_check.hpp"

namespace sympathy {

// Unresolved: the multipliers' own error (the trivial multiplier's, FloquetAnalysis::trivial_error)
// is above the stability tolerance and the largest other multiplier lies within it of the circle:
// the verdict would be the noise's (issue 33: AUTO's ab, pp2 and tor near their homoclinic orbits,
// trivial errors 1e-3 to 18, a verdict on every point).
enum class Stability { Stable, Unstable, Marginal, Unresolved };
std::string to_string(Stability s);

struct FloquetOptions {
  // Stable: every multiplier but the trivial and structural ones has |mu| < 1 - tolerance;
  // unstable: one has |mu| > 1 + tolerance; marginal otherwise. The tolerance is at least the
  // trivial multiplier's error (a verdict must hold within the multipliers' error). Default well
  // above the multipliers' measured errors (about 1e-8 at the default integrator settings).
  double stability_tolerance = 1e-6;

  OptionCheck validate() const {
    if (!(positive(stability_tolerance) && stability_tolerance < 1.0))
      return OptionProblem{"stability_tolerance", "a number in (0, 1)"};
    return std::nullopt;
  }
};

// Which perturbations a multiplier belongs to, where the orbit lies in a subspace that a symmetry
// keeps (a start's InvariantSubspace: anti-phase x = 0, th2 = -th1): those inside it keep the
// symmetry, those across it break it (a branch point of a breaking multiplier is the
// symmetry-breaking pitchfork). Unlabelled: no subspace was declared.
enum class SymmetryKind { Unlabelled, Keeping, Breaking };
std::string to_string(SymmetryKind k);  // "", "keeps", "breaks"

struct Multiplier {
  std::complex<double> value;
  double log_modulus = 0.0;  // log|value|, accurate even where |value| underflows
  bool trivial = false;      // the multiplier of the vector field's direction
  bool structural = false;   // forced to 1 by a family of orbits
  SymmetryKind symmetry = SymmetryKind::Unlabelled;  // see label_symmetry
  double modulus() const { return std::abs(value); }
};

struct FloquetAnalysis {
  std::vector<Multiplier> multipliers;  // by decreasing modulus
  int trivial = -1;                     // index of the trivial multiplier; -1 if none
  double trivial_error = 0.0;           // |mu_trivial - 1|
  double trivial_alignment = 0.0;       // |cos| of the angle between its eigenvector and f
  int structural = 0;                   // number of structural multipliers
  Stability stability = Stability::Marginal;
  double max_modulus = 0.0;  // largest |mu| among the others
  int unstable_count = 0;    // others with |mu| > 1 + tolerance
  // With symmetry labels: the largest |Q_across^T Phi Q_inside| / |Phi| over the segments, which
  // is zero when the subspace is invariant (the labels are given only below 1e-6).
  double symmetry_defect = 0.0;
};

// The product of the segments' transition matrices, last first: the monodromy matrix (formed;
// its eigenvalues are for analyze_floquet to take, its eigenvectors for whoever needs them).
Eigen::MatrixXd monodromy(const std::vector<Eigen::MatrixXd>& segments);

// `segments`: transition matrices of the m shooting segments in order (one: the monodromy).
// `flow_direction`: f at the orbit's initial point, or empty for a periodically forced
// (non-autonomous) system, which has no trivial multiplier. `family`: directions at the
// initial point along a continuum of orbits (columns; none for an isolated orbit): the
// multipliers whose eigenvectors lie along them are the structural ones, forced to 1.
FloquetAnalysis analyze_floquet(const std::vector<Eigen::MatrixXd>& segments,
                                const Eigen::VectorXd& flow_direction,
                                const Eigen::MatrixXd& family = Eigen::MatrixXd(),
                                const FloquetOptions& options = {});

// Labels every multiplier of `a` by the symmetry of its perturbations (SymmetryKind): the segment
// matrices of an orbit lying in an invariant subspace are block triangular in the basis
// (`inside`, `across`) of the subspace and its orthogonal complement (they map the subspace into
// itself), so the multipliers are the eigenvalues of the inside blocks' product and of the across
// blocks' product, each a periodic Schur decomposition of its own; each multiplier takes the kind
// of the block eigenvalue it pairs with (least total distance), the trivial one always with the
// subspace's block (f lies in it). Where the segments leak out of the subspace by more than 1e-6
// (the orbit does not lie in it), nothing is labelled.
void label_symmetry(FloquetAnalysis& a, const std::vector<Eigen::MatrixXd>& segments,
                    const Eigen::MatrixXd& inside, const Eigen::MatrixXd& across);

// The multipliers of an orbit of N identical units that all move alike, from those of one
// representative block: `a` analyses the orbit in the subspace where every unit but the first
// moves alike (its Keeping multipliers those of the symmetric motion, its Breaking ones those of
// the first unit against the rest). The permutations of the units make the whole monodromy
// block diagonal in the isotypic components, the breaking block repeated once for each of the
// N - 1 independent differences between units: each Breaking multiplier is repeated `copies`
// (N - 1) times in all, and the summary (stability, unstable count) follows.
FloquetAnalysis repeat_breaking(FloquetAnalysis a, int copies, const FloquetOptions& options);

}  // namespace sympathy
