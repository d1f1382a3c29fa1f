// The van der Pol oscillator as a C++ plug-in (cases/examples/vdp_plugin.toml names it):
//   x' = y,   y' = mu (1 - x^2) y - x.
// A plug-in is a PluginSystem (sympathy/core/plugin.hpp) with a templated right-hand side, so
// its Jacobian and variational equations come from the engine's dual numbers; its states and
// parameters are the case file's, in its order.
#include <sympathy/core/plugin.hpp>

class VanDerPol final : public sympathy::PluginSystem<VanDerPol> {
 public:
  using PluginSystem::PluginSystem;
  static constexpr int kDimension = 2, kParameters = 1;  // x, y; mu
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = z[1];
    dz[1] = p[0] * (1.0 - z[0] * z[0]) * z[1] - z[0];
  }
};

SYMPATHY_PLUGIN(VanDerPol)
