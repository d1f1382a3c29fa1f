#include "sympathy/cases/equation_codegen.hpp"

#include <charconv>
#include <map>
#include <numbers>
#include <stdexcept>

namespace sympathy {

namespace {

// Strings joined by append (GCC 12 warns falsely, -Wrestrict, on "literal" + std::string).
template <class... Parts>
std::string cat(const Parts&... parts) {
  std::string s;
  (s.append(parts), ...);
  return s;
}

// A double literal that reads back to the same value ("2" becomes "2.0": never int arithmetic).
std::string literal(double value) {
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  std::string s(buffer, result.ptr);
  if (s.find_first_of(".en") == std::string::npos) s += ".0";
  return s;
}

const char* function_code(Function f) {
  switch (f) {
    case Function::Sin:
      return "sin";
    case Function::Cos:
      return "cos";
    case Function::Tan:
      return "tan";
    case Function::Exp:
      return "exp";
    case Function::Log:
      return "log";
    case Function::Sqrt:
      return "sqrt";
    case Function::Abs:
      return "abs";
    case Function::Tanh:
      return "tanh";
    case Function::Atan:
      return "atan";
    case Function::Asin:
      return "asin";
    case Function::Acos:
      return "acos";
    case Function::Sinh:
      return "sinh";
    case Function::Cosh:
      return "cosh";
    case Function::Pow:
      return "pow";
    case Function::Atan2:
      return "atan2";
    case Function::Min:
      return "equations_min";
    case Function::Max:
      return "equations_max";
    case Function::SignSmooth:
      return "equations_sign_smooth";
    case Function::Sign:
      return "equations_sign";  // a switching surface's (Emitter::emit)
  }
  throw std::logic_error("unknown function");
}

class Emitter {
 public:
  explicit Emitter(const EquationSystem& system) {
    for (std::size_t i = 0; i < system.states.size(); ++i)
      identifiers_[system.states[i].name] = cat("s", std::to_string(i));
    for (std::size_t i = 0; i < system.parameters.size(); ++i)
      identifiers_[system.parameters[i].name] = cat("p", std::to_string(i));
    for (std::size_t i = 0; i < system.intermediates.size(); ++i)
      identifiers_[system.intermediates[i].name] = cat("w", std::to_string(i));
    identifiers_["t"] = "S(t)";
    identifiers_["pi"] = literal(std::numbers::pi);
    // Each sign(...) of the intermediates and derivatives is a switching surface, numbered in
    // the order they are written (its argument = 0; a sign inside another's argument too).
    for (const auto& w : system.intermediates) collect_surfaces(w.tree);
    for (const auto& d : system.derivatives) collect_surfaces(d.tree);
    // Then each impact's surface (a sign(...) inside it or its reset is the sign of its value).
    for (const auto& impact : system.impacts) surface_arguments_.push_back(&impact.surface);
  }

  // The switching surfaces' functions: the arguments of the sign calls, in surface order, then
  // the impacts' surfaces.
  const std::vector<const Expression*>& surfaces() const { return surface_arguments_; }

  using K = Expression::Kind;

  // a OP b without its own parentheses. A left operand of the same precedence goes without
  // parentheses too (C++ groups a + b - c as (a + b) - c, as the tree does), so a sum of 2000
  // terms is not 2000 nested parentheses (compilers limit nesting: clang at 256 by default).
  std::string binary(const Expression& e) const {
    const char* op = e.kind == K::Add        ? " + "
                     : e.kind == K::Subtract ? " - "
                     : e.kind == K::Multiply ? " * "
                                             : " / ";
    const auto& left = e.operands[0];
    const bool additive = e.kind == K::Add || e.kind == K::Subtract;
    const bool same = additive ? (left.kind == K::Add || left.kind == K::Subtract)
                               : (left.kind == K::Multiply || left.kind == K::Divide);
    return cat(same ? binary(left) : emit(left), op, emit(e.operands[1]));
  }

  // Every subexpression in parentheses: the tree's structure, not C++'s precedence, decides.
  std::string emit(const Expression& e) const {
    switch (e.kind) {
      case K::Number:
        return literal(e.number);
      case K::Name:
        return identifiers_.at(e.name);  // checked names only (the loader's)
      case K::Negate:
        return cat("(-", emit(e.operands[0]), ")");
      case K::Add:
      case K::Subtract:
      case K::Multiply:
      case K::Divide:
        return cat("(", binary(e), ")");
      case K::Power: {
        // An integer exponent as products (x^2 = x*x, as a hand-written model has it); any
        // other through pow.
        const auto& exponent = e.operands[1];
        if (exponent.kind == K::Number && exponent.number == static_cast<int>(exponent.number) &&
            exponent.number >= -64 && exponent.number <= 64)
          return cat("equations_ipow<", std::to_string(static_cast<int>(exponent.number)), ">(S(",
                     emit(e.operands[0]), "))");
        return cat("pow(S(", emit(e.operands[0]), "), S(", emit(exponent), "))");
      }
      case K::Call: {
        // sign(x): the region's sign of surface k where `sides` (the generated function's) names
        // a region, else the sign of x; a sign of parameters alone (a steep zone's width) is no
        // surface.
        if (e.function == Function::Sign) {
          const auto k = surface_of_.find(&e);
          return cat(
              "equations_sign(S(", emit(e.operands[0]), "), ",
              k == surface_of_.end() ? "nullptr, 0" : cat("sides, ", std::to_string(k->second)),
              ")");
        }
        std::string s = std::string(function_code(e.function)) + "(";
        for (std::size_t i = 0; i < e.operands.size(); ++i)
          s += cat(i ? ", S(" : "S(", emit(e.operands[i]), ")");
        return s + ")";
      }
    }
    throw std::logic_error("unknown expression kind");
  }

 private:
  void collect_surfaces(const Expression& e) {
    if (e.kind == K::Call && e.function == Function::Sign) {
      surface_of_[&e] = static_cast<int>(surface_arguments_.size());
      surface_arguments_.push_back(&e.operands[0]);
    }
    for (const auto& operand : e.operands) collect_surfaces(operand);
  }

  std::map<std::string, std::string> identifiers_;
  std::map<const Expression*, int> surface_of_;
  std::vector<const Expression*> surface_arguments_;
};

constexpr const char* kPrologue =
    R"(// Generated by sympathy (cases/equation_codegen.cpp) from the expression trees of an equation
// case file. Names: s = states, p = parameters, w = intermediates, in the order of the file.
#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <utility>
#include <vector>

#ifndef SYMPATHY_EQUATIONS_TAG
#error "SYMPATHY_EQUATIONS_TAG (the cache key) must be defined"
#endif

#include "sympathy/core/plugin.hpp"

namespace {

using sympathy::value_of;

template <int N, class S>
S equations_ipow(const S& a) {
  if constexpr (N < 0) {
    return 1.0 / equations_ipow<-N>(a);
  } else if constexpr (N == 0) {
    return S(1.0);
  } else if constexpr (N == 1) {
    return a;
  } else {
    const S half = equations_ipow<N / 2>(a);
    if constexpr (N % 2 == 0)
      return half * half;
    else
      return half * half * a;
  }
}
template <class S>
S equations_min(const S& a, const S& b) {
  return value_of(b) < value_of(a) ? b : a;
}
template <class S>
S equations_max(const S& a, const S& b) {
  return value_of(a) < value_of(b) ? b : a;
}
// sign_smooth(x, eps) = tanh(x / eps) (cases/expression.hpp).
template <class S>
S equations_sign_smooth(const S& x, const S& eps) {
  using std::tanh;
  return tanh(x / eps);
}
// sign(x): the sign of switching surface k in the region named by `sides` where given (a hybrid
// system's field of one region, extended beyond its surfaces), else of x itself; constant
// between surfaces (no derivative).
template <class S>
S equations_sign(const S& x, const int* sides, int k) {
  return S(sides ? static_cast<double>(sides[k]) : (value_of(x) >= 0.0 ? 1.0 : -1.0));
}
)";

constexpr const char* kSmoothClass = R"(
class GeneratedSystem final : public sympathy::PluginSystem<GeneratedSystem> {
 public:
  using PluginSystem::PluginSystem;
)";

// With sign(...) calls: a piecewise-smooth system (core/hybrid_system.hpp) whose regions are
// named by the signs of their arguments.
constexpr const char* kHybridClass = R"(
class GeneratedSystem final
    : public sympathy::PluginSystem<GeneratedSystem,
                                    sympathy::AutoDiffHybridSystem<GeneratedSystem>> {
 public:
  using PluginSystem::PluginSystem;
)";

constexpr const char* kEpilogue = R"(};

}  // namespace

SYMPATHY_PLUGIN(GeneratedSystem)
)";

// The impacts' surfaces (the last ones): their directions, names and resets, the resets'
// derivatives in the states and parameters by dual numbers.
std::string impact_declarations(const EquationSystem& system, const Emitter& emitter,
                                const std::string& preamble) {
  const std::string n = std::to_string(system.states.size());
  const std::string m = std::to_string(system.parameters.size());
  const std::size_t first = emitter.surfaces().size() - system.impacts.size();
  std::string s =
      "  int crossing_direction(int surface) const override {\n    switch (surface) {\n";
  for (std::size_t k = 0; k < system.impacts.size(); ++k)
    s += "      case " + std::to_string(first + k) + ": return " +
         std::to_string(system.impacts[k].direction) + ";\n";
  s += "      default: return 0;\n    }\n  }\n\n";
  s += "  bool has_reset(int surface) const override { return surface >= " + std::to_string(first) +
       "; }\n\n";
  s += "  std::string switching_name(int surface) const override {\n";
  s += "    return surface >= " + std::to_string(first) +
       " ? \"impacts[\" + std::to_string(surface - " + std::to_string(first) +
       " + 1) + \"].surface = 0\" : \"switching surface \" + std::to_string(surface);\n  }\n\n";
  s += "  template <class S>\n";
  s += "  void resets([[maybe_unused]] double t, const S* z, [[maybe_unused]] const S* p, int "
       "surface, S* out) const {\n";
  s += "    [[maybe_unused]] const int* sides = nullptr;\n" + preamble;
  s += "    for (int i = 0; i < " + n + "; ++i) out[i] = z[i];\n    switch (surface) {\n";
  for (std::size_t k = 0; k < system.impacts.size(); ++k) {
    s += "      case " + std::to_string(first + k) + ":\n";
    for (const auto& [state, tree] : system.impacts[k].reset)
      s += "        out[" + std::to_string(state) + "] = S(" + emitter.emit(tree) + ");\n";
    s += "        break;\n";
  }
  s += "      default:\n        break;\n    }\n  }\n\n";
  s +=
      "  void reset(double t, const double* z, const double* p, int surface, double* z_plus) const "
      "override {\n    resets(t, z, p, surface, z_plus);\n  }\n\n";
  s += "  void reset_jacobian(double t, const double* z, const double* p, int surface, "
       "Eigen::MatrixXd& r_z) const override {\n";
  s += "    using D = sympathy::Dual<1>;\n";
  s += "    std::vector<D> zd(z, z + " + n + "), pd(p, p + " + m + "), out(" + n + ");\n";
  s += "    r_z.resize(" + n + ", " + n + ");\n";
  s += "    for (int j = 0; j < " + n + "; ++j) {\n";
  s += "      zd[j].d[0] = 1.0;\n      resets(t, zd.data(), pd.data(), surface, out.data());\n";
  s += "      for (int i = 0; i < " + n + "; ++i) r_z(i, j) = out[i].d[0];\n";
  s += "      zd[j].d[0] = 0.0;\n    }\n  }\n\n";
  s += "  void reset_parameter_derivative(double t, const double* z, const double* p, int surface, "
       "int parameter, double* r_p) const override {\n";
  s += "    using D = sympathy::Dual<1>;\n";
  s += "    std::vector<D> zd(z, z + " + n + "), pd(p, p + " + m + "), out(" + n + ");\n";
  s += "    pd[parameter].d[0] = 1.0;\n    resets(t, zd.data(), pd.data(), surface, out.data());\n";
  s += "    for (int i = 0; i < " + n + "; ++i) r_p[i] = out[i].d[0];\n  }\n\n";
  return s;
}

// A piecewise-smooth system's surfaces (the sign calls' arguments), their gradients in the
// states by dual numbers, dh/dt by a central difference where the system uses t (1e-6 of |t|, at
// least 1e-6: a truncation error of about 1e-12 relative), dh/dp by dual numbers, their names.
std::string hybrid_declarations(const EquationSystem& system, const Emitter& emitter,
                                const std::string& preamble) {
  const auto& surfaces = emitter.surfaces();
  const std::string n = std::to_string(system.states.size());
  const std::string m = std::to_string(system.parameters.size());
  std::string s = "  int switching_count() const override { return " +
                  std::to_string(surfaces.size()) + "; }\n\n";
  s += "  template <class S>\n";
  s += "  void surfaces([[maybe_unused]] double t, const S* z, [[maybe_unused]] const S* p, S* g) "
       "const {\n";
  s += "    [[maybe_unused]] const int* sides = nullptr;\n" + preamble;
  for (std::size_t k = 0; k < surfaces.size(); ++k)
    s += "    g[" + std::to_string(k) + "] = S(" + emitter.emit(*surfaces[k]) + ");\n";
  s += "  }\n\n";
  s += "  void switching_functions(double t, const double* z, const double* p, double* g) const "
       "override {\n    surfaces(t, z, p, g);\n  }\n\n";
  s += "  double switching_gradient(double t, const double* z, const double* p, int surface, "
       "double* h_z) const override {\n";
  s += "    using D = sympathy::Dual<1>;\n";
  s += "    std::vector<D> zd(z, z + " + n + "), pd(p, p + " + m + "), gd(switching_count());\n";
  s += "    for (int j = 0; j < " + n + "; ++j) {\n";
  s += "      zd[j].d[0] = 1.0;\n      surfaces(t, zd.data(), pd.data(), gd.data());\n";
  s += "      h_z[j] = gd[surface].d[0];\n      zd[j].d[0] = 0.0;\n    }\n";
  if (system.uses_time) {
    s += "    const double dt = 1e-6 * std::max(1.0, std::abs(t));\n";
    s += "    std::vector<double> up(switching_count()), down(switching_count());\n";
    s += "    surfaces(t + dt, z, p, up.data());\n    surfaces(t - dt, z, p, down.data());\n";
    s += "    return (up[surface] - down[surface]) / (2.0 * dt);\n  }\n\n";
  } else {
    s += "    return 0.0;\n  }\n\n";
  }
  s += "  double switching_parameter_derivative(double t, const double* z, const double* p, int "
       "surface, int parameter) const override {\n";
  s += "    using D = sympathy::Dual<1>;\n";
  s += "    std::vector<D> zd(z, z + " + n + "), pd(p, p + " + m + "), gd(switching_count());\n";
  s += "    pd[parameter].d[0] = 1.0;\n    surfaces(t, zd.data(), pd.data(), gd.data());\n";
  s += "    return gd[surface].d[0];\n  }\n\n";
  if (!system.impacts.empty()) s += impact_declarations(system, emitter, preamble);
  return s;
}

}  // namespace

std::string generate_equation_source(const EquationSystem& system) {
  const Emitter emitter(system);
  const std::size_t n = system.states.size(), m = system.parameters.size();
  const auto& surfaces = emitter.surfaces();
  const bool hybrid = !surfaces.empty();
  std::string s = kPrologue;
  s += hybrid ? kHybridClass : kSmoothClass;
  s += "  int dimension() const override { return " + std::to_string(n) + "; }\n";
  s += std::string("  bool autonomous() const override { return ") +
       (system.uses_time ? "false" : "true") + "; }\n";
  std::string angles;
  for (std::size_t i = 0; i < n; ++i)
    if (system.states[i].angle) angles += (angles.empty() ? "" : ", ") + std::to_string(i);
  if (!angles.empty())
    s += "  std::vector<int> angle_states() const override { return {" + angles + "}; }\n";
  s += "\n";
  // The states, parameters and intermediates as S, in a function with z and p (and `sides`).
  std::string preamble =
      "    using std::abs, std::acos, std::asin, std::atan, std::atan2, std::cos, std::cosh,\n"
      "        std::exp, std::log, std::pow, std::sin, std::sinh, std::sqrt, std::tan, "
      "std::tanh;\n";
  for (std::size_t i = 0; i < n; ++i)
    preamble +=
        "    [[maybe_unused]] const S s" + std::to_string(i) + " = z[" + std::to_string(i) + "];\n";
  for (std::size_t i = 0; i < m; ++i)
    preamble +=
        "    [[maybe_unused]] const S p" + std::to_string(i) + " = p[" + std::to_string(i) + "];\n";
  for (std::size_t i = 0; i < system.intermediates.size(); ++i)
    preamble += "    [[maybe_unused]] const S w" + std::to_string(i) + " = " +
                emitter.emit(system.intermediates[i].tree) + ";\n";
  s += "  template <class T, class P>\n";
  if (hybrid) {
    // The field read off the state's own region, and the field of a named region.
    s += "  void evaluate(double t, const T* z, const P* p, T* dz) const {\n"
         "    evaluate_on_sides(t, z, p, dz, nullptr);\n  }\n\n";
    s += "  template <class T, class P>\n";
    s += "  void evaluate_on_sides([[maybe_unused]] double t, const T* z, [[maybe_unused]] const "
         "P* p, T* dz, [[maybe_unused]] const int* sides) const {\n";
  } else {
    s += "  void evaluate([[maybe_unused]] double t, const T* z, [[maybe_unused]] const P* p, "
         "T* dz) const {\n";
  }
  s += "    using S = decltype(T() + P());\n" + preamble;
  for (std::size_t i = 0; i < n; ++i)
    s += "    dz[" + std::to_string(i) + "] = " + emitter.emit(system.derivatives[i].tree) + ";\n";
  s += "  }\n\n";
  if (hybrid) s += hybrid_declarations(system, emitter, preamble);
  // A function of the parameters alone, in doubles (steep zones' sizes, the forcing's period).
  auto parameter_function = [&](const std::string& signature) {
    std::string f = "  " + signature + " const override {\n";
    f += "    using S = double;\n";
    f += "    using std::abs, std::acos, std::asin, std::atan, std::atan2, std::cos, std::cosh,\n"
         "        std::exp, std::log, std::pow, std::sin, std::sinh, std::sqrt, std::tan, "
         "std::tanh;\n";
    for (std::size_t i = 0; i < m; ++i)
      f += "    [[maybe_unused]] const S p" + std::to_string(i) + " = p[" + std::to_string(i) +
           "];\n";
    return f;
  };
  if (system.forcing_period)
    s += parameter_function("double forcing_period(const double* p)") + "    return S(" +
         emitter.emit(*system.forcing_period) + ");\n  }\n\n";
  if (!system.steep.empty()) {
    // The zones' sizes from the parameters (sympathy::SteepZone{component, width, scale}).
    s += parameter_function("std::vector<sympathy::SteepZone> steep_zones(const double* p)");
    s += "    std::vector<sympathy::SteepZone> zones;\n";
    for (const auto& zone : system.steep) {
      const std::string width = "S(" + emitter.emit(zone.width) + ")";
      const std::string scale = zone.scale ? "S(" + emitter.emit(*zone.scale) + ")"
                                           : "std::max(1.0, 10.0 * " + width + ")";
      s += "    zones.push_back({" + std::to_string(zone.state) + ", " + width + ", " + scale +
           "});\n";
    }
    s += "    return zones;\n  }\n\n";
  }
  s += "  static constexpr int kDimension = " + std::to_string(n) + ";\n";
  s += "  static constexpr int kParameters = " + std::to_string(m) + ";\n";
  s += kEpilogue;
  return s;
}

}  // namespace sympathy
