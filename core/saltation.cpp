// The saltation matrix and the crossings of one instant (see saltation.hpp).
#include "sympathy/core/saltation.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

namespace sympathy {

namespace {

// h_z f + h_t, the rate at which a field f moves h, and whether it moves h at all: beyond the
// grazing tolerance against its parts (a field tangent to the surface decides no side).
struct SurfaceRate {
  double value = 0.0;
  bool transversal = false;
};
SurfaceRate surface_rate(const Eigen::VectorXd& f, const Eigen::RowVectorXd& h_z, double h_t) {
  const double rate = h_z.dot(f) + h_t;
  return {rate, std::abs(rate) > kGrazingTolerance * (h_z.norm() * f.norm() + std::abs(h_t))};
}

// h_z f- + h_t, the rate at which the flow arrives at the surface; refused where it is too small
// against its parts for the crossing time to have a derivative (a grazing).
double arrival_rate(const Eigen::VectorXd& f_minus, const Eigen::RowVectorXd& h_z, double h_t,
                    double t, const std::string& surface) {
  const auto [rate, transversal] = surface_rate(f_minus, h_z, h_t);
  if (!transversal) {
    std::ostringstream msg;
    msg.precision(12);
    msg << "grazing: the flow touches " << surface << " at t = " << t << " (h_z f + h_t = " << rate
        << "); the flow has no derivative there";
    throw NonsmoothFlowError(msg.str(), t);
  }
  return rate;
}

// Past a surface crossed without a reset, the new region's field must carry the flow on (h_z f+ +
// h_t of the arrival's sign): where it points back, both fields push towards the surface and the
// solution slides along it (Filippov), which no region's field describes; refused with that name.
void check_not_sliding(const Eigen::VectorXd& f_plus, const Eigen::RowVectorXd& h_z, double h_t,
                       double arrival, double t, const std::string& surface) {
  const auto [rate, transversal] = surface_rate(f_plus, h_z, h_t);
  if (rate * arrival < 0.0 && transversal) {
    std::ostringstream msg;
    msg.precision(12);
    msg << "sliding: at t = " << t << " the fields on both sides of " << surface
        << " push towards it (h_z f + h_t = " << arrival << " before, " << rate
        << " after the crossing): the solution slides along the surface, which the flow does not "
           "follow";
    throw NonsmoothFlowError(msg.str(), t);
  }
}

int sign_of(double x) {
  return x > 0.0 ? 1 : -1;
}

// The crossings in the given order, one after the other.
HybridEvent cross_in_order(const HybridSystem& system, double t, const Eigen::VectorXd& z,
                           const ParameterValues& p, const std::vector<int>& sides,
                           const std::vector<int>& order, std::span<const int> parameters,
                           bool derivatives) {
  const int n = system.dimension();
  const int np = static_cast<int>(parameters.size());
  HybridEvent event;
  event.state = z;
  event.sides = sides;
  if (derivatives) {
    event.saltation = Eigen::MatrixXd::Identity(n, n);
    event.parameter_jump = Eigen::MatrixXd::Zero(n, np);
  }
  Eigen::VectorXd f_minus(n), f_plus(n), z_plus(n), r_p(n);
  Eigen::RowVectorXd h_z(n);
  Eigen::MatrixXd r_z;
  for (int surface : order) {
    const Eigen::VectorXd z_minus = event.state;
    system.rhs_on_sides(t, z_minus.data(), p.data(), event.sides.data(), f_minus.data());
    const double h_t = system.switching_gradient(t, z_minus.data(), p.data(), surface, h_z.data());
    const std::string name = system.switching_name(surface);
    const double rate = arrival_rate(f_minus, h_z, h_t, t, name);
    const bool reset = system.has_reset(surface);
    if (reset) {
      system.reset(t, z_minus.data(), p.data(), surface, z_plus.data());
      // After a jump the flow goes where f points at z+ (an impact: back where it came from).
      Eigen::VectorXd f(n);
      Eigen::RowVectorXd g_z(n);
      system.rhs(t, z_plus.data(), p.data(), f.data());
      const double g_t = system.switching_gradient(t, z_plus.data(), p.data(), surface, g_z.data());
      event.sides[surface] = sign_of(arrival_rate(f, g_z, g_t, t, name));
    } else {
      z_plus = z_minus;
      event.sides[surface] = -event.sides[surface];
    }
    event.state = z_plus;
    system.rhs_on_sides(t, z_plus.data(), p.data(), event.sides.data(), f_plus.data());
    if (!reset) check_not_sliding(f_plus, h_z, h_t, rate, t, name);
    if (!derivatives) continue;
    if (reset)
      system.reset_jacobian(t, z_minus.data(), p.data(), surface, r_z);
    else
      r_z = Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd jump_direction = (f_plus - r_z * f_minus) / rate;
    const Eigen::MatrixXd s = r_z + jump_direction * h_z;
    Eigen::MatrixXd b(n, np);
    for (int k = 0; k < np; ++k) {
      if (reset)
        system.reset_parameter_derivative(t, z_minus.data(), p.data(), surface, parameters[k],
                                          r_p.data());
      else
        r_p.setZero();
      const double h_p = system.switching_parameter_derivative(t, z_minus.data(), p.data(), surface,
                                                               parameters[k]);
      b.col(k) = r_p + jump_direction * h_p;
    }
    // Composition: x+ = S (S_prev x + b_prev) + b.
    event.parameter_jump = s * event.parameter_jump + b;
    event.saltation = s * event.saltation;
  }
  return event;
}

}  // namespace

Eigen::MatrixXd saltation_matrix(const Eigen::VectorXd& f_minus, const Eigen::VectorXd& f_plus,
                                 const Eigen::RowVectorXd& h_z, double h_t,
                                 const Eigen::MatrixXd& r_z) {
  return r_z + (f_plus - r_z * f_minus) * h_z / (h_z.dot(f_minus) + h_t);
}

Eigen::VectorXd parameter_jump(const Eigen::VectorXd& f_minus, const Eigen::VectorXd& f_plus,
                               const Eigen::RowVectorXd& h_z, double h_t,
                               const Eigen::MatrixXd& r_z, double h_p, const Eigen::VectorXd& r_p) {
  return r_p + (f_plus - r_z * f_minus) * (h_p / (h_z.dot(f_minus) + h_t));
}

HybridEvent cross_surfaces(const HybridSystem& system, double t, const Eigen::VectorXd& z,
                           const ParameterValues& p, const std::vector<int>& sides,
                           std::span<const int> surfaces, std::span<const int> parameters,
                           bool derivatives) {
  std::vector<int> order(surfaces.begin(), surfaces.end());
  HybridEvent event = cross_in_order(system, t, z, p, sides, order, parameters, derivatives);
  if (!derivatives || order.size() < 2) return event;
  // A perturbation decides which surface is hit first: the flow is differentiable only if the
  // orders agree. The ascending and the descending order are compared (for two surfaces, every
  // order).
  std::reverse(order.begin(), order.end());
  const HybridEvent reversed = cross_in_order(system, t, z, p, sides, order, parameters, true);
  const auto largest = [](const Eigen::MatrixXd& m) {
    return m.size() == 0 ? 0.0 : m.cwiseAbs().maxCoeff();
  };
  const double scale = std::max({largest(event.saltation), largest(event.parameter_jump),
                                 largest(reversed.saltation), largest(reversed.parameter_jump)});
  const double difference = std::max(largest(event.saltation - reversed.saltation),
                                     largest(event.parameter_jump - reversed.parameter_jump));
  event.order_difference = scale > 0.0 ? difference / scale : 0.0;
  if (event.order_difference > kCornerTolerance) {
    std::ostringstream msg;
    msg.precision(6);
    msg << "corner: switching surfaces";
    for (int s : surfaces) msg << (s == surfaces.front() ? " " : ", ") << system.switching_name(s);
    msg << " are crossed at one instant, t = " << t
        << ", and their saltation matrices do not commute (the two orders differ by "
        << event.order_difference << ", relative); the flow has no derivative there";
    throw NonsmoothFlowError(msg.str(), t);
  }
  return event;
}

StartSide side_entered(const HybridSystem& system, double t, const Eigen::VectorXd& z,
                       const ParameterValues& p, std::vector<int> sides, int surface,
                       const Eigen::VectorXd& field) {
  const int n = system.dimension();
  Eigen::RowVectorXd h_z(n);
  const double h_t = system.switching_gradient(t, z.data(), p.data(), surface, h_z.data());
  const int along_field = h_z.dot(field) + h_t < 0.0 ? -1 : 1;
  if (system.has_reset(surface) || system.crossing_direction(surface) != 0)
    return {along_field, ""};
  // Each side's field: the rate it moves h at, and whether it leaves the surface.
  Eigen::VectorXd f(n);
  double rate[2];
  bool leaves[2];
  for (int k = 0; k < 2; ++k) {
    sides[surface] = k == 0 ? 1 : -1;
    system.rhs_on_sides(t, z.data(), p.data(), sides.data(), f.data());
    const SurfaceRate r = surface_rate(f, h_z, h_t);
    rate[k] = r.value;
    leaves[k] = r.transversal;
  }
  // Where both fields leave the surface or both arrive: the state, the surface and both rates,
  // for the message that says so.
  const auto both_sides = [&](int precision, const char* push) {
    std::ostringstream msg;
    msg.precision(precision);
    msg << "at t = " << t << " the state lies on " << system.switching_name(surface) << push
        << " (h_z f + h_t = " << rate[0] << " on its positive side, " << rate[1]
        << " on its negative side)";
    return msg.str();
  };
  const bool both = leaves[0] && leaves[1];
  if (both && rate[0] < 0.0 && rate[1] > 0.0)
    throw NonsmoothFlowError(
        "sliding: " + both_sides(12, " and the fields on both sides push towards it") +
            ": the solution slides along the surface, which the flow does "
            "not follow",
        t);
  if (both && rate[0] > 0.0 && rate[1] < 0.0)
    return {along_field,
            "two solutions: " + both_sides(6, ", which the fields on both sides push away from") +
                "; followed: the one into its " + (along_field > 0 ? "positive" : "negative") +
                " side, where the field at the state points"};
  if (leaves[0]) return {rate[0] > 0.0 ? 1 : -1, ""};
  if (leaves[1]) return {rate[1] > 0.0 ? 1 : -1, ""};
  return {along_field, ""};
}

}  // namespace sympathy
