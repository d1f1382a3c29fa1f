#include "vector_ops.hpp"

#include <cmath>
#include <vector>

namespace sympathy::detail {

namespace {

// z = sum_i c[i] x[i] entry by entry, for K vectors known at compile time: the loop over the
// vectors unrolled, the one over the entries free to vectorize. Each entry's terms are added in
// SUNDIALS's order (c[0] x[0], then + c[1] x[1], ...), so the sums round alike; z[j] is written
// after every x[i][j] is read, so z may be any x[i]. With c[0] = 1 the first product is x[0][j]
// itself, as SUNDIALS's in-place case leaves it.
template <int K>
void combine(const sunrealtype* c, const sunrealtype* const* x, sunrealtype* z, sunindextype n) {
  sunrealtype ci[K];
  const sunrealtype* xi[K];
  for (int i = 0; i < K; ++i) {
    ci[i] = c[i];
    xi[i] = x[i];
  }
  for (sunindextype j = 0; j < n; ++j) {
    sunrealtype sum = ci[0] * xi[0][j];
    for (int i = 1; i < K; ++i) sum += ci[i] * xi[i][j];
    z[j] = sum;
  }
}

}  // namespace

int linear_combination(int nvec, sunrealtype* c, N_Vector* X, N_Vector z) {
  if (nvec < 1) return -1;
  // One or two vectors: scale and linear sum (below), as SUNDIALS's, which allow z to be X[1].
  if (nvec == 1) {
    scale(c[0], X[0], z);
    return 0;
  }
  if (nvec == 2) {
    linear_sum(c[0], X[0], c[1], X[1], z);
    return 0;
  }
  const sunindextype n = NV_LENGTH_S(z);
  sunrealtype* zd = NV_DATA_S(z);
  // ARKODE's explicit stages combine 3 to 8 vectors (Dormand-Prince: up to 7): unrolled, as one
  // pass over the entries instead of one per vector (10.7% of the fast preset's instructions on
  // the anti-phase branch, at 470 a call).
  using Combine =
      void (*)(const sunrealtype*, const sunrealtype* const*, sunrealtype*, sunindextype);
  static constexpr Combine kUnrolled[] = {combine<3>, combine<4>, combine<5>,
                                          combine<6>, combine<7>, combine<8>};
  if (nvec <= 8) {
    const sunrealtype* x[8];
    for (int i = 0; i < nvec; ++i) x[i] = NV_DATA_S(X[i]);
    kUnrolled[nvec - 3](c, x, zd, n);
    return 0;
  }
  const sunrealtype* x0 = NV_DATA_S(X[0]);
  // z = c[0] X[0] first (in place where z is X[0]; nothing to do for c[0] = 1), then each term
  // added in turn: SUNDIALS's order of operations, so the sums round alike.
  if (X[0] != z) {
    for (sunindextype j = 0; j < n; ++j) zd[j] = c[0] * x0[j];
  } else if (c[0] != 1.0) {
    for (sunindextype j = 0; j < n; ++j) zd[j] *= c[0];
  }
  for (int i = 1; i < nvec; ++i) {
    const sunrealtype* xi = NV_DATA_S(X[i]);
    const sunrealtype ci = c[i];
    for (sunindextype j = 0; j < n; ++j) zd[j] += ci * xi[j];
  }
  return 0;
}

void linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  const sunrealtype* xd = NV_DATA_S(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype* zd = NV_DATA_S(z);
  // SUNDIALS's cases, by the rounding they give: with a or b = +-1, a x + b y (the product by +-1
  // is exact, whichever of its special loops runs); otherwise a (x + y) where a = b (0 included),
  // a (x - y) where a = -b, else a x + b y. Each entry is read before it is written, so z may be
  // x or y.
  const bool unit = a == 1.0 || a == -1.0 || b == 1.0 || b == -1.0;
  if (!unit && a == b) {
    for (sunindextype j = 0; j < n; ++j) zd[j] = a * (xd[j] + yd[j]);
  } else if (!unit && a == -b) {
    for (sunindextype j = 0; j < n; ++j) zd[j] = a * (xd[j] - yd[j]);
  } else {
    for (sunindextype j = 0; j < n; ++j) zd[j] = a * xd[j] + b * yd[j];
  }
}

void absolute(N_Vector x, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  const sunrealtype* xd = NV_DATA_S(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype j = 0; j < n; ++j) zd[j] = std::fabs(xd[j]);
}

void inverse(N_Vector x, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  const sunrealtype* xd = NV_DATA_S(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype j = 0; j < n; ++j) zd[j] = 1.0 / xd[j];
}

void add_constant(N_Vector x, sunrealtype b, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  const sunrealtype* xd = NV_DATA_S(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype j = 0; j < n; ++j) zd[j] = xd[j] + b;
}

void scale(sunrealtype c, N_Vector x, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  const sunrealtype* xd = NV_DATA_S(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype j = 0; j < n; ++j) zd[j] = c * xd[j];  // c = 1 and -1 are exact too
}

sunrealtype weighted_rms_norm(N_Vector x, N_Vector w) {
  const sunindextype n = NV_LENGTH_S(x);
  const sunrealtype* xd = NV_DATA_S(x);
  const sunrealtype* wd = NV_DATA_S(w);
  sunrealtype sum = 0.0;
  for (sunindextype j = 0; j < n; ++j) {
    const sunrealtype p = xd[j] * wd[j];
    sum += p * p;
  }
  const sunrealtype mean = sum / static_cast<sunrealtype>(n);
  return mean <= 0.0 ? 0.0 : std::sqrt(mean);
}

void set_constant(sunrealtype c, N_Vector z) {
  const sunindextype n = NV_LENGTH_S(z);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype j = 0; j < n; ++j) zd[j] = c;
}

namespace {
// z = a x + y, as every case of SUNDIALS's linear sum with b = 1 gives it (a x + y, x + y, y - x:
// the product by 1 or -1 is exact); z may be y.
void add_scaled(sunrealtype a, const sunrealtype* x, const sunrealtype* y, sunrealtype* z,
                sunindextype n) {
  for (sunindextype j = 0; j < n; ++j) z[j] = a * x[j] + y[j];
}
}  // namespace

int scale_add_multi(int nvec, sunrealtype* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  if (nvec < 1) return -1;
  if (nvec == 1) {  // SUNDIALS's goes to its linear sum
    linear_sum(a[0], x, 1.0, Y[0], Z[0]);
    return 0;
  }
  const sunindextype n = NV_LENGTH_S(x);
  for (int i = 0; i < nvec; ++i)
    add_scaled(a[i], NV_DATA_S(x), NV_DATA_S(Y[i]), NV_DATA_S(Z[i]), n);
  return 0;
}

int linear_sum_vector_array(int nvec, sunrealtype a, N_Vector* X, sunrealtype b, N_Vector* Y,
                            N_Vector* Z) {
  if (nvec < 1) return -1;
  // SUNDIALS's picks its case from a and b alone, the same for every vector: linear_sum's.
  for (int i = 0; i < nvec; ++i) linear_sum(a, X[i], b, Y[i], Z[i]);
  return 0;
}

int scale_vector_array(int nvec, sunrealtype* c, N_Vector* X, N_Vector* Z) {
  if (nvec < 1) return -1;
  for (int i = 0; i < nvec; ++i) scale(c[i], X[i], Z[i]);
  return 0;
}

int constant_vector_array(int nvec, sunrealtype c, N_Vector* Z) {
  if (nvec < 1) return -1;
  for (int i = 0; i < nvec; ++i) set_constant(c, Z[i]);
  return 0;
}

int weighted_rms_norm_vector_array(int nvec, N_Vector* X, N_Vector* W, sunrealtype* nrm) {
  if (nvec < 1) return -1;
  for (int i = 0; i < nvec; ++i) nrm[i] = weighted_rms_norm(X[i], W[i]);
  return 0;
}

int scale_add_multi_vector_array(int nvec, int nsum, sunrealtype* a, N_Vector* X, N_Vector** Y,
                                 N_Vector** Z) {
  if (nvec < 1 || nsum < 1) return -1;
  // One sum: SUNDIALS's goes to its linear sum (of arrays); otherwise, one vector or many, each
  // Z[j][i] = a[j] X[i] + Y[j][i].
  if (nsum == 1) return linear_sum_vector_array(nvec, a[0], X, 1.0, Y[0], Z[0]);
  const sunindextype n = NV_LENGTH_S(X[0]);
  for (int i = 0; i < nvec; ++i)
    for (int j = 0; j < nsum; ++j)
      add_scaled(a[j], NV_DATA_S(X[i]), NV_DATA_S(Y[j][i]), NV_DATA_S(Z[j][i]), n);
  return 0;
}

int linear_combination_vector_array(int nvec, int nsum, sunrealtype* c, N_Vector** X, N_Vector* Z) {
  if (nvec < 1 || nsum < 1) return -1;
  // Per vector j, the linear combination of X[0][j] .. X[nsum-1][j]: SUNDIALS's cases (one sum:
  // a scale; two: a linear sum; more: c[0] X[0][j] first, then each term added in turn, in place
  // where Z is X[0]) are linear_combination's.
  constexpr int kOnStack = 16;
  N_Vector on_stack[kOnStack];
  std::vector<N_Vector> on_heap;
  N_Vector* column = on_stack;
  if (nsum > kOnStack) {
    on_heap.resize(nsum);
    column = on_heap.data();
  }
  for (int j = 0; j < nvec; ++j) {
    for (int i = 0; i < nsum; ++i) column[i] = X[i][j];
    linear_combination(nsum, c, column, Z[j]);
  }
  return 0;
}

void use_project_vector_ops(N_Vector v) {
  v->ops->nvlinearcombination = linear_combination;
  v->ops->nvscale = scale;
  v->ops->nvwrmsnorm = weighted_rms_norm;
  v->ops->nvlinearsum = linear_sum;
  v->ops->nvabs = absolute;
  v->ops->nvinv = inverse;
  v->ops->nvaddconst = add_constant;
  v->ops->nvconst = set_constant;
  v->ops->nvscaleaddmulti = scale_add_multi;
  v->ops->nvlinearsumvectorarray = linear_sum_vector_array;
  v->ops->nvscalevectorarray = scale_vector_array;
  v->ops->nvconstvectorarray = constant_vector_array;
  v->ops->nvwrmsnormvectorarray = weighted_rms_norm_vector_array;
  v->ops->nvscaleaddmultivectorarray = scale_add_multi_vector_array;
  v->ops->nvlinearcombinationvectorarray = linear_combination_vector_array;
}

}  // namespace sympathy::detail
