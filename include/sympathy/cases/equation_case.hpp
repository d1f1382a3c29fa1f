// Equation case files: a system written as equations in a TOML case file (kind = "equations"),
// read, parsed (expression.hpp) and checked whole before anything is compiled or run.
//
//   kind = "equations"
//   name = "hopf"                     # optional, as in every case file
//   description = "..."
//   forcing_period = "2*pi/beta"      # optional, for equations that use t: the forcing's period
//                                     # (parameters only), which a forced system's orbits have
//   [states]                          # the state vector, in the order of the file; initial values
//   x = 0.1                           # or a table: theta = { value = 0.0, angle = true }, an
//   y = 0.0                           # angle (a rotation by 2 pi k per period is periodic)
//   [parameters]                      # a value, or a table with value, unit, min, max
//   mu = 0.25
//   w = { value = 1.0, unit = "rad/s", min = 0.0 }
//   [intermediates]                   # optional; evaluated in the order of the file
//   r2 = "x^2 + y^2"
//   [equations]                       # one per state: its time derivative
//   x = "mu*x - w*y - x*r2"
//   y = "w*x + mu*y - y*r2"
//   [steep]                           # optional: states near whose zero f changes steeply
//   vth1 = "eps/50"                   # the zone's half-width (an expression of parameters), or
//   vth2 = { width = "eps/50", scale = "1" }   # with the state's typical size away from it
//   [params.NAME]                     # optional parameter sets, as in metronome case files
//   [starts.NAME]                     # optional named starts: state values (others: [states])
//   default_params = "NAME"
//
// Or a C++ plug-in instead of [intermediates], [equations] and [steep]: `plugin = "FILE.cpp"`,
// a source beside the case file defining a PluginSystem (core/plugin.hpp) whose states and
// parameters are the file's, in its order. A plug-in is code: it is compiled and run as it is.
//
// Names: the time `t` and the constant `pi` are built in. Every name of the file is an ASCII
// identifier (a letter, then letters, digits and '_'), at most 64 characters, no "__", not a
// function of the grammar, not t or pi, not a C++ keyword, and unique across states,
// parameters and intermediates. An intermediate uses only names defined above it. The whole
// file is ASCII (comments included) and at most kMaxEquationFileBytes. Every error is an
// InputError "FILE:LINE:COLUMN: key 'KEY': expected WHAT, got WHAT".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/expression.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

constexpr std::size_t kMaxEquationFileBytes = 1 << 20;

struct EquationState {
  std::string name;
  double initial = 0.0;
  // Declared an angle (theta = { value = 0.0, angle = true }): a motion on which it gains 2 pi k
  // per period is periodic (OdeSystem::angle_states).
  bool angle = false;
};

struct EquationParameter {
  std::string name;
  double value = 0.0;
  std::string unit;  // as the file says it; "" if not given
  std::optional<double> min, max;
  std::string source;  // "FILE:LINE: key 'parameters.NAME'"
};

struct NamedExpression {
  std::string name;  // the intermediate's name, or the state whose derivative this is
  Expression tree;
};

// A state near whose zero the equations change steeply (an escapement switching with the sign of
// a velocity): the flow resolves its crossings (SteepZone, core/ode_system.hpp). Width and scale
// are expressions of the parameters; without a scale, max(1, 10 width).
struct SteepSpec {
  int state = 0;
  Expression width;
  std::optional<Expression> scale;
};

// An impact: where the motion reaches the surface h(t, z, p) = 0 in `direction` (-1: where h
// decreases, the free region h > 0; +1: where it increases), the states named in `reset` jump to
// their expressions' values, of the states just before (the others keep theirs): a ball's
// velocity reversed at a wall, v = -e*v. The system is then a hybrid one (core/hybrid_system.hpp)
// with a reset on that surface.
struct ImpactSpec {
  Expression surface;
  int direction = -1;
  std::vector<std::pair<int, Expression>> reset;  // (state, its value after), in state order
};

// A checked system of equations: what code generation needs, and nothing of the file's text.
struct EquationSystem {
  std::vector<EquationState> states;
  std::vector<EquationParameter> parameters;
  std::vector<NamedExpression> intermediates;  // in evaluation order
  std::vector<NamedExpression> derivatives;    // one per state, in state order
  bool uses_time = false;                      // does any expression use t?
  std::vector<SteepSpec> steep;                // [steep], in state order
  std::vector<ImpactSpec> impacts;             // [[impacts]], in file order
  std::optional<Expression> forcing_period;    // of parameters; only where uses_time
};

class EquationCase {
 public:
  // Reads and checks an equation case file; throws InputError.
  static EquationCase load(const std::string& path);

  const std::string& path() const { return path_; }
  // The C++ plug-in's source (`plugin = "FILE.cpp"`, resolved beside the case file); empty for a
  // file of equations.
  const std::string& plugin() const { return plugin_; }
  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  const EquationSystem& system() const { return system_; }
  const std::string& default_parameter_set() const { return default_params_; }
  std::vector<std::string> parameter_set_names() const;
  std::vector<std::string> start_names() const;
  std::vector<std::string> state_names() const;
  std::vector<std::string> parameter_names() const;

  // The parameter values (in parameter order) of set `params` (empty: the file's default, if
  // any) with the assignments on top, each checked against the parameter's bounds. Throws
  // InputError naming where the value came from.
  Eigen::VectorXd parameter_values(const std::string& params = "",
                                   const std::vector<Assignment>& sets = {}) const;

  const StartSpec& start(const std::string& name) const;  // throws InputError
  // The [states] values, then a start's, then the assignments (state names).
  Eigen::VectorXd initial_state(const StartSpec* start,
                                const std::vector<Assignment>& initial = {}) const;

 private:
  std::string path_;
  std::string plugin_;
  std::string name_;
  std::string description_;
  std::string default_params_;
  EquationSystem system_;
  std::vector<ParameterSet> parameter_sets_;
  std::vector<StartSpec> starts_;
};

// What a case file is: "equations" for an equation case file (kind = "equations"), "metronomes"
// for a metronome-platform case file (no kind key, or kind = "metronomes"). Throws InputError
// for a missing or unreadable file or another kind.
std::string case_file_kind(const std::string& path);

}  // namespace sympathy
