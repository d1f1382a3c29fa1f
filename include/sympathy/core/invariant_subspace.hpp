// A subspace of states that a symmetry keeps: components tied by z_a = sign * z_b, or z_a = 0.
// Orbits that lie in such a subspace (an anti-phase orbit, whose platform stays still) can be
// reached by integrating inside it, however unstable they are in the full space: projecting
// after every stretch of integration keeps rounding errors from growing along the unstable
// directions, which all point out of the subspace.
#pragma once

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

class InvariantSubspace {
 public:
  InvariantSubspace() = default;  // the whole space
  // Relations between components of an n-dimensional state; throws std::invalid_argument if
  // one names a component outside 0..n-1. `description`: how people name it ("x = 0, th2 =
  // -th1"), for reports of the symmetry a multiplier breaks.
  InvariantSubspace(int dimension, const std::vector<ComponentRelation>& relations,
                    std::string description = "");

  bool is_whole_space() const { return groups_.empty(); }
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
};

}  // namespace sympathy
