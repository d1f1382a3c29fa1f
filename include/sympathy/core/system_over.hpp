// A system built on another one (a restriction to a subspace, or an extension by variational
// equations): its parameters, their values and defaults, its autonomy, forcing period and
// switching functions' count are the wrapped system's. ReducedSystem and AcrossVariations are
// built on it; what differs (dimension, names, f and its derivatives) they define.
#pragma once

#include <string>
#include <vector>

#include "sympathy/core/ode_system.hpp"

namespace sympathy {

class SystemOver : public OdeSystem {
 public:
  std::vector<std::string> parameter_names() const override { return system_.parameter_names(); }
  ParameterValues default_parameters() const override { return system_.default_parameters(); }
  double parameter(const ParameterValues& p, int index) const override {
    return system_.parameter(p, index);
  }
  void set_parameter(ParameterValues& p, int index, double value) const override {
    system_.set_parameter(p, index, value);
  }
  bool autonomous() const override { return system_.autonomous(); }
  double forcing_period(const double* p) const override { return system_.forcing_period(p); }
  int switching_count() const override { return system_.switching_count(); }

 protected:
  // `system` must outlive this.
  explicit SystemOver(const OdeSystem& system) : system_(system) {}
  const OdeSystem& system_;
};

}  // namespace sympathy
