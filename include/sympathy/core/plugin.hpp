// A system compiled into a shared library that sympathy loads at run time: the C interface of
// every such library, and the base class of its system. Equation case files' generated code
// (cases/equation_codegen.cpp) and C++ plug-ins (a case file's `plugin = "FILE.cpp"`) both end in
// SYMPATHY_PLUGIN(Class), which exports
//   int sympathy_equations_abi(void)              kPluginAbi, the layout of what follows
//   const char* sympathy_equations_tag(void)      the cache key it was built under
//                                                 (SYMPATHY_EQUATIONS_TAG, given at compile time)
//   const char* sympathy_equations_binary_interface(void)
//                                                 kBinaryInterface as the library was compiled
//                                                 (core/binary_interface.hpp): must equal the
//                                                 program's
//   void* sympathy_equations_create(const char* const* states, int n,
//                                   const char* const* parameters, const double* values, int m)
//                                                 a new sympathy::OdeSystem (nullptr on a
//                                                 mismatch of n, m or an exception)
//   void sympathy_equations_destroy(void* system)
//
// A plug-in's class derives from PluginSystem<Class> and writes the templated right-hand side
// (as every AutoDiffSystem does); its states and parameters are the case file's, in its order,
// their names and values passed at creation:
//
//   #include <sympathy/core/plugin.hpp>
//   class VanDerPol final : public sympathy::PluginSystem<VanDerPol> {
//    public:
//     using PluginSystem::PluginSystem;
//     static constexpr int kDimension = 2, kParameters = 1;  // checked against the case file
//     template <class T, class P>
//     void evaluate(double, const T* z, const P* p, T* dz) const {
//       dz[0] = z[1];
//       dz[1] = p[0] * (1.0 - z[0] * z[0]) * z[1] - z[0];
//     }
//   };
//   SYMPATHY_PLUGIN(VanDerPol)
#pragma once

#include <exception>
#include <string>
#include <utility>
#include <vector>

#include "sympathy/core/autodiff_hybrid_system.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "sympathy/core/binary_interface.hpp"

namespace sympathy {

constexpr int kPluginAbi = 3;  // 2: with sympathy_equations_binary_interface; 3: Taylor jets

// Base: AutoDiffSystem<Derived>, or AutoDiffHybridSystem<Derived> for a piecewise-smooth system
// (which then writes evaluate_on_sides and its surfaces too, core/autodiff_hybrid_system.hpp).
template <class Derived, class Base = AutoDiffSystem<Derived>>
class PluginSystem : public Base {
 public:
  // -1: any number (then dimension() is the number of states named).
  static constexpr int kDimension = -1, kParameters = -1;

  PluginSystem(std::vector<std::string> states, std::vector<NamedParameter> named,
               std::vector<double> values)
      : states_(std::move(states)) {
    this->set_parameter_layout(std::move(named), std::move(values));
  }
  int dimension() const override { return static_cast<int>(states_.size()); }
  std::vector<std::string> state_names() const override { return states_; }

 private:
  std::vector<std::string> states_;
};

}  // namespace sympathy

#ifndef SYMPATHY_EQUATIONS_TAG
#define SYMPATHY_EQUATIONS_TAG "untagged"
#endif

#define SYMPATHY_PLUGIN(Class)                                                                     \
  extern "C" {                                                                                     \
  __attribute__((visibility("default"))) int sympathy_equations_abi() {                            \
    return sympathy::kPluginAbi;                                                                   \
  }                                                                                                \
  __attribute__((visibility("default"))) const char* sympathy_equations_binary_interface() {       \
    return sympathy::kBinaryInterface;                                                             \
  }                                                                                                \
  __attribute__((visibility("default"))) const char* sympathy_equations_tag() {                    \
    return SYMPATHY_EQUATIONS_TAG;                                                                 \
  }                                                                                                \
  __attribute__((visibility("default"))) void* sympathy_equations_create(                          \
      const char* const* states, int n, const char* const* parameters, const double* values,       \
      int m) {                                                                                     \
    if ((Class::kDimension >= 0 && n != Class::kDimension) ||                                      \
        (Class::kParameters >= 0 && m != Class::kParameters))                                      \
      return nullptr;                                                                              \
    try {                                                                                          \
      std::vector<std::string> names(states, states + n);                                          \
      std::vector<sympathy::NamedParameter> named;                                                 \
      for (int i = 0; i < m; ++i) named.push_back({parameters[i], {i}, 1.0});                      \
      return static_cast<sympathy::OdeSystem*>(                                                    \
          new Class(std::move(names), std::move(named), std::vector<double>(values, values + m))); \
    } catch (...) { /* whatever the class throws: nothing crosses the C interface */               \
      return nullptr;                                                                              \
    }                                                                                              \
  }                                                                                                \
  __attribute__((visibility("default"))) void sympathy_equations_destroy(void* system) {           \
    delete static_cast<sympathy::OdeSystem*>(system);                                              \
  }                                                                                                \
  }
