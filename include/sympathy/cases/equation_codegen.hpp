// C++ source of a checked EquationSystem (equation_case.hpp), generated from its expression trees
// alone: a class derived from AutoDiffSystem whose templated evaluate() is the right-hand side, so
// the Jacobian, the variational equations and df/dp come from the engine's dual numbers exactly
// as for a model written by hand.
//
// No text of the case file reaches the source: states are s0, s1, ..., parameters p0, ...,
// intermediates w0, ..., numbers are printed from their parsed values, operators and functions
// come from the grammar's enumerations; names, units and descriptions reach the system at run
// time, as arguments of the library's factory. The library's C interface:
//   int sympathy_equations_abi(void)              kEquationAbi, the layout of what follows
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
#pragma once

#include <string>

#include "sympathy/cases/equation_case.hpp"

namespace sympathy {

constexpr int kEquationAbi = 2;  // 2: with sympathy_equations_binary_interface

std::string generate_equation_source(const EquationSystem& system);

}  // namespace sympathy
