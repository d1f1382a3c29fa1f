// A subspace of states that a symmetry keeps: components tied by z_a = sign * z_b, or z_a = 0.
// Orbits that lie in such a subspace (an anti-phase orbit, whose platform stays still) can be
// reached by integrating inside it, however unstable they are in the full space: projecting
// after every stretch of integration keeps rounding errors from growing along the unstable
// directions, which all point out of the subspace.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/core/ode_system.hpp"

namespace sympathy {

struct ComponentRelation {
  int component = 0;
  int other = -1;  // -1: component = 0
  double sign = 1.0;
};

// Largest |f(g z) - g f(z)| relative to |f(z)| at a few sample states z (each component drawn
// from [-scale_i, scale_i]): about 1e-16 where the linear map g is a symmetry of f at p, O(1)
// where it is not.
double equivariance_defect(const OdeSystem& system, const ParameterValues& p,
                           const Eigen::VectorXd& scale,
                           const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& g);

// Units whose every permutation the system keeps (identical metronomes on a platform that treats
// them alike): each unit's state components, the same number per unit and in the same order.
// S_N acts by permuting the units. Declared by a case; `defect` checks it at parameter values.
struct PermutationSymmetry {
  std::vector<std::vector<int>> units;
  std::string description;  // how people name the units ("metronomes 1-64")

  // Largest |f(sigma z) - sigma f(z)| relative to |f| over the adjacent transpositions (which
  // generate S_N) at a few sample states: about 1e-16 for a symmetry of f at p, O(1) otherwise.
  double defect(const OdeSystem& system, const ParameterValues& p,
                const Eigen::VectorXd& scale) const;
  // Every unit's state in z permuted by swapping units a and b.
  Eigen::VectorXd swapped(Eigen::VectorXd z, int a, int b) const;
};

// A signed permutation g of the state components, (g z)_i = sign_i z_(image_i), with g g = I: the
// reflection whose fixed space is a subspace of ties between pairs (InvariantSubspace::reflection;
// the anti-phase orbit's "x = 0, th2 = -th1": the two pendula swapped with their signs flipped, the
// platform's sign flipped). Where f(g z) = g f(z) (checked: equivariance_defect), the Jacobian at a
// state of the fixed space commutes with g, so it maps the fixed space (g's +1 eigenspace) and its
// orthogonal complement (the -1 eigenspace) each into itself: the two isotypic components of Z2, in
// which the variational equations split into two blocks.
struct Reflection {
  std::vector<int> image;
  std::vector<double> sign;
  Eigen::VectorXd apply(const Eigen::VectorXd& z) const;
  // An orthonormal basis (columns) of g's -1 eigenspace, the directions that break the symmetry:
  // e_i for each component whose sign g flips in place, (e_a - s e_b) / sqrt(2) for each pair g
  // swaps with sign s.
  Eigen::MatrixXd breaking_basis() const;
};

class InvariantSubspace {
 public:
  InvariantSubspace() = default;  // the whole space
  // Relations between components of an n-dimensional state; throws std::invalid_argument if
  // one names a component outside 0..n-1. `description`: how people name it ("x = 0, th2 =
  // -th1"), for reports of the symmetry a multiplier breaks.
  InvariantSubspace(int dimension, const std::vector<ComponentRelation>& relations,
                    std::string description = "");

  bool is_whole_space() const { return groups_.empty(); }
  // The subspace that every permutation of `symmetry`'s units keeps (each unit's state equal to
  // the first's), remembering the symmetry.
  static InvariantSubspace fixed_by(const PermutationSymmetry& symmetry, int dimension,
                                    std::string description);
  // The symmetry whose fixed space this is, where one was declared (with_symmetry).
  const std::optional<PermutationSymmetry>& symmetry() const { return symmetry_; }
  // This subspace, declared to be the fixed space of `symmetry`; throws std::invalid_argument if
  // it is not (different relations).
  InvariantSubspace with_symmetry(PermutationSymmetry symmetry, int dimension) const;

  // Representative coordinates of the subspace: one for each component in no relation and one
  // for each tied group that is not zero (its smallest component), in increasing order of those
  // components. A state of the subspace is z_c = sign_c * y_(coordinate_c), 0 where
  // coordinate_c is -1.
  struct Coordinates {
    std::vector<int> representative;  // per coordinate: its component
    std::vector<int> coordinate;      // per component: its coordinate, or -1 (a zero component)
    std::vector<double> sign;         // per component
    int size() const { return static_cast<int>(representative.size()); }
    Eigen::VectorXd embed(const Eigen::VectorXd& y) const;  // z from y
    // z from y into z's n entries, for right-hand sides (no allocation).
    void embed_into(const double* y, double* z) const {
      const int n = static_cast<int>(coordinate.size());
      for (int c = 0; c < n; ++c) z[c] = coordinate[c] < 0 ? 0.0 : sign[c] * y[coordinate[c]];
    }
    Eigen::VectorXd restrict(const Eigen::VectorXd& z) const;  // y: z's representatives
    // The same as matrices: P (n x r, z = P y) and R (r x n, y = R z).
    Eigen::MatrixXd embedding() const;
    Eigen::MatrixXd restriction() const;
  };
  Coordinates coordinates(int dimension) const;
  // The reflection whose fixed space this is, where there is one: every tied group holds one or
  // two components (a zero group's components change sign, a pair is swapped with the sign that
  // ties it); nullopt for the whole space and where a group ties three or more components (S_N,
  // not Z2: symmetry_reduction.hpp).
  std::optional<Reflection> reflection(int dimension) const;
  // This subspace as a subspace of `larger` (which contains it), in larger's coordinates.
  InvariantSubspace within(const InvariantSubspace& larger, int dimension) const;
  // Whether two subspaces of a space of `dimension` components are the same.
  bool same_as(const InvariantSubspace& other, int dimension) const;
  const std::string& description() const { return description_; }
  // Orthonormal bases (columns) of the subspace and of its orthogonal complement, in a state
  // space of `dimension` components: the directions that keep the symmetry and those that
  // break it.
  Eigen::MatrixXd basis(int dimension) const;
  Eigen::MatrixXd complement(int dimension) const;
  // Both from one eigendecomposition of the projector.
  struct Bases {
    Eigen::MatrixXd inside, across;
  };
  Bases bases(int dimension) const;
  // Orthogonal projection onto the subspace.
  Eigen::VectorXd project(const Eigen::VectorXd& z) const;
  // Largest |(I - P) f(t, P z; p)| relative to |f| over a few sample states: about 1e-16 when the
  // system keeps the subspace at parameter values p, O(1) when it does not.
  double invariance_defect(const OdeSystem& system, const ParameterValues& p,
                           const Eigen::VectorXd& scale) const;

 private:
  struct Member {
    int component;
    double sign;
  };
  // Components tied together, with signs relative to the first; `zero`: the group is 0.
  struct Group {
    std::vector<Member> members;
    bool zero = false;
  };
  Eigen::MatrixXd projector(int dimension) const;  // the orthogonal projection, as a matrix

  std::vector<Group> groups_;
  std::string description_;
  std::optional<PermutationSymmetry> symmetry_;
};

}  // namespace sympathy
