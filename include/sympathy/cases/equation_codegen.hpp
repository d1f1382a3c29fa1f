// C++ source of a checked EquationSystem (equation_case.hpp), generated from its expression trees
// alone: a class derived from AutoDiffSystem whose templated evaluate() is the right-hand side, so
// the Jacobian, the variational equations and df/dp come from the engine's dual numbers exactly
// as for a model written by hand.
//
// No text of the case file reaches the source: states are s0, s1, ..., parameters p0, ...,
// intermediates w0, ..., numbers are printed from their parsed values, operators and functions
// come from the grammar's enumerations; names, units and descriptions reach the system at run
// time, as arguments of the library's factory (the C interface of core/plugin.hpp, which the
// source ends with, as a C++ plug-in does).
#pragma once

#include <string>

#include "sympathy/cases/equation_case.hpp"
#include "sympathy/core/plugin.hpp"

namespace sympathy {

constexpr int kEquationAbi = kPluginAbi;

std::string generate_equation_source(const EquationSystem& system);

}  // namespace sympathy
