// A system of one's own, its periodic orbit found and continued until the branch folds.
//
// The normal form of a fold of cycles, x' = -y + x g, y' = x + y g with g = mu + 2 r^2 - r^4
// and r^2 = x^2 + y^2, is r' = r g, theta' = 1 in polar form: circles of period 2 pi wherever
// g = 0, i.e. at mu = r^4 - 2 r^2. That is smallest at r^2 = 1, so the stable outer cycle and
// the unstable inner one meet at mu = -1 exactly, where the radial multiplier
// exp(2 pi * 4 r^2 (1 - r^2)) passes through 1: the fold (LP) must be found at mu = -1.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "sympathy/continuation/branch_run.hpp"
#include "sympathy/core/autodiff_system.hpp"

class FoldOfCycles final : public sympathy::AutoDiffSystem<FoldOfCycles> {
 public:
  FoldOfCycles() { set_parameter_layout({{"mu", {0}}}, {-0.5}); }  // two cycles: r^2 = 1 +- 0.71
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  // T: double or a dual number (derivatives come from it); P likewise for the parameter values.
  template <class T, class P>
  void evaluate(double /*t*/, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    const T g = p[0] + 2.0 * r2 - r2 * r2;
    dz[0] = -z[1] + z[0] * g;
    dz[1] = z[0] + z[1] * g;
  }
};

int main() {
  const FoldOfCycles system;
  sympathy::BranchProblem problem;  // what to continue; parameter values travel with it
  problem.parameter = system.parameter_index("mu");
  problem.values = system.default_parameters();
  problem.from = -0.5;  // from the stable outer cycle at mu = -0.5 down, through the fold,
  problem.to = -1.5;    // and back up the inner one to the bound
  problem.start_state = Eigen::Vector2d(1.0, 0.0);
  const sympathy::Branch branch = sympathy::continue_branch(system, problem, {});
  if (!branch.started()) return 1;

  bool fold = false;
  for (const sympathy::Bifurcation& e : branch.events) {
    std::printf("%s at mu = %.10f +- %.1e\n", sympathy::to_string(e.type).c_str(), e.parameter,
                e.uncertainty);
    fold |= e.type == sympathy::BifurcationType::Fold && std::abs(e.parameter + 1.0) < 1e-6;
  }
  std::printf("%zu points, stopped: %s; %.2f s\n", branch.points.size(), branch.stop_reason.c_str(),
              branch.seconds);
  return fold ? 0 : 1;
}
