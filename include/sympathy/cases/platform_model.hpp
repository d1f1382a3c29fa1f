// The platform with its pendula locked to their casings (MODEL.md; the paper identifies the
// platform's damping and stiffness this way): nothing of the pendula moves, their masses ride
// on the platform, and each direction is a damped oscillator
//   Mt x'' + cx x' + kx x = 0   (and Mt y'' + cy y' + ky y = 0 on a 2-D platform),
//   Mt = M + sum_i (mp_i + mb_i).
// State: z = [x, (y), vx, (vy)], named as in the full model. Parameters keep the full model's
// names for everything that enters: M, c, k (cx, cy, kx, ky when 2-D), the shared pendulum
// masses mp and mb and the per-metronome ones mp1, mb1, ...
#pragma once

#include <string>
#include <vector>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/core/autodiff_system.hpp"

namespace sympathy {

class PlatformModel final : public AutoDiffSystem<PlatformModel> {
 public:
  explicit PlatformModel(const ModelSpec& spec);

  int dimension() const override { return 2 * directions_; }
  std::vector<std::string> state_names() const override;
  int platform_directions() const { return directions_; }
  // Mt = M + sum of the pendulum masses, at parameter values p.
  double total_mass(const ParameterValues& p) const;

  template <class T, class P>
  void evaluate(double /*t*/, const T* z, const P* raw, T* dz) const {
    // Raw layout: [M, cx, cy, kx, ky], then (mp, mb) per metronome.
    P Mt = raw[0];
    for (int i = 0; i < metronomes_; ++i) Mt = Mt + raw[5 + 2 * i] + raw[6 + 2 * i];
    const int D = directions_;
    for (int a = 0; a < D; ++a) {
      dz[a] = z[D + a];
      dz[D + a] = (-raw[1 + a] * z[D + a] - raw[3 + a] * z[a]) / Mt;
    }
  }

 private:
  int directions_;
  int metronomes_;
};

}  // namespace sympathy
