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

Eigen::VectorXd OdeSystem::rhs(double t, const Eigen::VectorXd& z, const ParameterValues& p) const {
  Eigen::VectorXd dz(dimension());
  rhs(t, z.data(), p.data(), dz.data());
  return dz;
}

Eigen::MatrixXd OdeSystem::jacobian(double t, const Eigen::VectorXd& z,
                                    const ParameterValues& p) const {
  Eigen::MatrixXd jac(dimension(), dimension());
  jacobian(t, z.data(), p.data(), jac);
  return jac;
}

void OdeSystem::check_parameters(const ParameterValues& p) const {
  const int expected = parameter_values_size();
  if (p.size() != expected)
    throw std::invalid_argument("parameter values have " + std::to_string(p.size()) +
                                " entries; the system has " + std::to_string(expected));
  if (!p.allFinite()) throw std::invalid_argument("parameter values are not finite");
}

}  // namespace sympathy
