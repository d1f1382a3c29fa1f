// Serial N_Vector operations compiled with the project (private to core).
//
// Debian's SUNDIALS 6.4.1 builds its serial N_VLinearCombination far slower than the same loop
// compiled here: 214 ns against 43 ns for five 18-entry vectors, 573 ns against 123 ns for 48
// (g++ -O2, this 2-core machine, 2026-11-25), and on the fast preset's anti-phase k-branch that one
// operation took 29% of all instructions (ARKODE's stages and solutions: about seven calls a
// step, callgrind). The integrators' vectors use this one instead; it computes the same sums in
// the same order, so the results are the same to the bit (tested).
#pragma once

#include <nvector/nvector_serial.h>

namespace sympathy::detail {

// z = sum_i c[i] X[i], as N_VLinearCombination_Serial: z may be X[0] (then z = c[0] z + ...),
// and with two vectors X[1]; with more, not another X[i]. One or two vectors go to scale and
// linear_sum (below), as SUNDIALS's goes to its N_VScale and N_VLinearSum.
int linear_combination(int nvec, sunrealtype* c, N_Vector* X, N_Vector z);

// z = a x + b y (z may be x or y), as N_VLinearSum_Serial: a (x + y) where a = b and
// a (x - y) where a = -b, unless a or b is +-1 (2.1% of the fast preset's instructions, at 200-500
// instructions a call for 20-30 entries, in SUNDIALS's).
void linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z);
// |x|, 1 / x and x + b, as N_VAbs_Serial, N_VInv_Serial and N_VAddConst_Serial: ARKODE's error
// weights at every step (2.1% there).
void absolute(N_Vector x, N_Vector z);
void inverse(N_Vector x, N_Vector z);
void add_constant(N_Vector x, sunrealtype b, N_Vector z);

// z = c x (z may be x), as N_VScale_Serial (2.9% of the fast preset's instructions there).
void scale(sunrealtype c, N_Vector x, N_Vector z);
// sqrt(sum_i (x_i w_i)^2 / n), as N_VWrmsNorm_Serial, the error test's norm (3.1%), summed in the
// same order.
sunrealtype weighted_rms_norm(N_Vector x, N_Vector w);

// z = c (N_VConst_Serial): CVODES clears its sensitivity corrections with it at every step.
void set_constant(sunrealtype c, N_Vector z);
// Z[i] = a[i] x + Y[i], i < nvec (N_VScaleAddMulti_Serial; Y may be Z).
int scale_add_multi(int nvec, sunrealtype* a, N_Vector x, N_Vector* Y, N_Vector* Z);

// The vector-array operations of CVODES's forward-sensitivity module, one vector (or one sum) at a
// time through the operations above, each as SUNDIALS's treats it: the same cases and the same
// order of operations, so the same bits. Debian's build took 55% of a period with the monodromy
// of 64 metronomes (130 states, 131 sensitivity vectors; perf, 2026-11-27): the weighted norms
// 13%, the scaled additions 11%, the linear sums 19%, the linear combinations 6%.
// Z[i] = a X[i] + b Y[i] (N_VLinearSumVectorArray_Serial; Z may be X or Y).
int linear_sum_vector_array(int nvec, sunrealtype a, N_Vector* X, sunrealtype b, N_Vector* Y,
                            N_Vector* Z);
// Z[i] = c[i] X[i] (N_VScaleVectorArray_Serial; Z may be X).
int scale_vector_array(int nvec, sunrealtype* c, N_Vector* X, N_Vector* Z);
// Z[i] = c (N_VConstVectorArray_Serial).
int constant_vector_array(int nvec, sunrealtype c, N_Vector* Z);
// nrm[i] = the weighted RMS norm of X[i] with W[i] (N_VWrmsNormVectorArray_Serial).
int weighted_rms_norm_vector_array(int nvec, N_Vector* X, N_Vector* W, sunrealtype* nrm);
// Z[j][i] = a[j] X[i] + Y[j][i], i < nvec, j < nsum (N_VScaleAddMultiVectorArray_Serial; Y may
// be Z).
int scale_add_multi_vector_array(int nvec, int nsum, sunrealtype* a, N_Vector* X, N_Vector** Y,
                                 N_Vector** Z);
// Z[j] = sum_i c[i] X[i][j], i < nsum, j < nvec (N_VLinearCombinationVectorArray_Serial; Z may
// be X[0]).
int linear_combination_vector_array(int nvec, int nsum, sunrealtype* c, N_Vector** X, N_Vector* Z);

// Makes `v` (a serial vector with fused operations enabled) and every vector cloned from it use
// the operations above.
void use_project_vector_ops(N_Vector v);

}  // namespace sympathy::detail
