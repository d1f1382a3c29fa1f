#include "sympathy/core/ode_system.hpp"

#include <stdexcept>

#include "sympathy/core/text.hpp"

namespace sympathy {

int OdeSystem::parameter_index(std::string_view name) const {
  const auto names = parameter_names();
  for (int i = 0; i < static_cast<int>(names.size()); ++i) {
    if (names[i] == name) return i;
  }
  const std::string known = join(names);
  throw std::invalid_argument("unknown parameter '" + std::string(name) +
                              "'; expected one of: " + known);
}

Eigen::VectorXd OdeSystem::rhs(double t, const Eigen::VectorXd& z) const {
  Eigen::VectorXd dz(dimension());
  rhs(t, z.data(), dz.data());
  return dz;
}

Eigen::MatrixXd OdeSystem::jacobian(double t, const Eigen::VectorXd& z) const {
  Eigen::MatrixXd jac(dimension(), dimension());
  jacobian(t, z.data(), jac);
  return jac;
}

}  // namespace sympathy
