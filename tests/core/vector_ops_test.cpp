// The project's serial vector operations (core/vector_ops.hpp) against SUNDIALS's own, to the
// bit: every number of vectors the integrators use (1 to 8, ARKODE's seven-stage pairs and CVODE's
// Nordsieck arrays), every aliasing SUNDIALS allows (z = X[0] with c[0] = 1 and otherwise; z = X[1]
// with two vectors), short and long vectors. The same sums in the same order give the same
// rounding, so a flow is the same to the bit with either.
#include <gtest/gtest.h>

#include <deque>
#include <random>
#include <vector>

#include <sundials/sundials_context.h>

#include "core/vector_ops.hpp"

namespace sympathy {
namespace {

struct Vectors {
  explicit Vectors(SUNContext ctx, int length, int count, std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1e3, 1e3);
    for (int i = 0; i < count; ++i) {
      v.push_back(N_VNew_Serial(length, ctx));
      for (int j = 0; j < length; ++j) NV_Ith_S(v.back(), j) = u(rng);
    }
  }
  ~Vectors() {
    for (N_Vector x : v) N_VDestroy(x);
  }
  std::vector<N_Vector> v;
};

std::vector<double> data(N_Vector x) {
  return std::vector<double>(NV_DATA_S(x), NV_DATA_S(x) + NV_LENGTH_S(x));
}

TEST(VectorOps, LinearCombinationIsSundialsToTheBit) {
  SUNContext ctx;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (int length : {1, 18, 48, 133}) {
    for (int nvec = 1; nvec <= 10; ++nvec) {  // 3-8 unrolled, more in a loop
      std::vector<double> c(nvec);
      for (double& ci : c) ci = u(rng);
      // Aliasing: 0 none, 1 z = X[0] with c[0] = 1, 2 z = X[0] otherwise, 3 z = X[1] (two vectors).
      for (int alias = 0; alias < 4; ++alias) {
        if (alias == 3 && nvec != 2) continue;
        SCOPED_TRACE(::testing::Message()
                     << "length " << length << ", " << nvec << " vectors, aliasing " << alias);
        std::mt19937 same(length * 100 + nvec * 10 + alias);
        Vectors ours(ctx, length, nvec + 1, same);
        same.seed(length * 100 + nvec * 10 + alias);
        Vectors theirs(ctx, length, nvec + 1, same);
        std::vector<double> k = c;
        if (alias == 1) k[0] = 1.0;
        const int z = alias == 0 ? nvec : alias == 3 ? 1 : 0;
        ASSERT_EQ(detail::linear_combination(nvec, k.data(), ours.v.data(), ours.v[z]), 0);
        ASSERT_EQ(N_VLinearCombination_Serial(nvec, k.data(), theirs.v.data(), theirs.v[z]), 0);
        EXPECT_EQ(data(ours.v[z]), data(theirs.v[z]));
      }
    }
  }
  std::vector<double> c{1.0};
  Vectors none(ctx, 3, 1, rng);
  EXPECT_EQ(detail::linear_combination(0, c.data(), none.v.data(), none.v[0]), -1);
  SUNContext_Free(&ctx);
}

// Scale (in place and not, c = 1, -1 and others) and the weighted RMS norm, to the bit.
TEST(VectorOps, ScaleAndNormAreSundialsToTheBit) {
  SUNContext ctx;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  std::mt19937 rng(11);
  for (int length : {1, 18, 48, 133}) {
    for (double c : {1.0, -1.0, 0.37, -2.5e3}) {
      for (bool in_place : {false, true}) {
        SCOPED_TRACE(::testing::Message()
                     << "length " << length << ", c " << c << (in_place ? ", in place" : ""));
        std::mt19937 same(length + static_cast<int>(in_place));
        Vectors ours(ctx, length, 2, same);
        same.seed(length + static_cast<int>(in_place));
        Vectors theirs(ctx, length, 2, same);
        detail::scale(c, ours.v[0], ours.v[in_place ? 0 : 1]);
        N_VScale_Serial(c, theirs.v[0], theirs.v[in_place ? 0 : 1]);
        EXPECT_EQ(data(ours.v[in_place ? 0 : 1]), data(theirs.v[in_place ? 0 : 1]));
      }
    }
    Vectors xw(ctx, length, 2, rng);
    EXPECT_EQ(detail::weighted_rms_norm(xw.v[0], xw.v[1]), N_VWrmsNorm_Serial(xw.v[0], xw.v[1]));
    N_VConst(0.0, xw.v[0]);
    EXPECT_EQ(detail::weighted_rms_norm(xw.v[0], xw.v[1]), 0.0);
  }
  SUNContext_Free(&ctx);
}

// The linear sum for every case SUNDIALS's treats apart (a or b = 1 or -1, a = b, a = -b, zero,
// others) and every aliasing (z = x, z = y, neither), and |x|, 1 / x, x + b: to the bit.
TEST(VectorOps, LinearSumAbsInverseAndAddConstAreSundialsToTheBit) {
  SUNContext ctx;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  const double coefficients[] = {1.0, -1.0, 0.0, 0.37, -0.37, 2.5, -1e-3};
  for (int length : {1, 18, 48, 133}) {
    for (double a : coefficients) {
      for (double b : coefficients) {
        for (int alias = 0; alias < 3; ++alias) {  // z: a third vector, x, y
          SCOPED_TRACE(::testing::Message() << "length " << length << ", a " << a << ", b " << b
                                            << ", aliasing " << alias);
          std::mt19937 same(length * 10 + alias);
          Vectors ours(ctx, length, 3, same);
          same.seed(length * 10 + alias);
          Vectors theirs(ctx, length, 3, same);
          const int z = alias == 0 ? 2 : alias - 1;
          detail::linear_sum(a, ours.v[0], b, ours.v[1], ours.v[z]);
          N_VLinearSum_Serial(a, theirs.v[0], b, theirs.v[1], theirs.v[z]);
          EXPECT_EQ(data(ours.v[z]), data(theirs.v[z]));
        }
      }
    }
    std::mt19937 same(length);
    Vectors ours(ctx, length, 2, same);
    same.seed(length);
    Vectors theirs(ctx, length, 2, same);
    detail::absolute(ours.v[0], ours.v[1]);
    N_VAbs_Serial(theirs.v[0], theirs.v[1]);
    EXPECT_EQ(data(ours.v[1]), data(theirs.v[1]));
    detail::inverse(ours.v[0], ours.v[1]);
    N_VInv_Serial(theirs.v[0], theirs.v[1]);
    EXPECT_EQ(data(ours.v[1]), data(theirs.v[1]));
    detail::add_constant(ours.v[0], 0.3, ours.v[1]);
    N_VAddConst_Serial(theirs.v[0], 0.3, theirs.v[1]);
    EXPECT_EQ(data(ours.v[1]), data(theirs.v[1]));
  }
  SUNContext_Free(&ctx);
}

// Vector arrays, as CVODES's forward-sensitivity module uses them: `count` arrays of `nvec`
// vectors each, with the same random entries for ours and SUNDIALS's.
struct Arrays {
  Arrays(SUNContext ctx, int length, int count, int nvec, unsigned seed) {
    std::mt19937 rng(seed);
    for (int k = 0; k < count; ++k) {
      vectors.emplace_back(ctx, length, nvec, rng);
      arrays.push_back(vectors.back().v.data());
    }
  }
  std::deque<Vectors> vectors;
  std::vector<N_Vector*> arrays;
  std::vector<std::vector<double>> contents() const {
    std::vector<std::vector<double>> all;
    for (const Vectors& v : vectors)
      for (N_Vector x : v.v) all.push_back(data(x));
    return all;
  }
};

// The vector-array operations of the sensitivity module, every case SUNDIALS's treats apart (one
// vector, one or two sums, coefficients 1, -1, equal and opposite, in place and not), to the bit.
TEST(VectorOps, VectorArrayOperationsAreSundialsToTheBit) {
  SUNContext ctx;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  const double coefficients[] = {1.0, -1.0, 0.0, 0.37, -0.37, 2.5};
  unsigned seed = 1;
  for (int length : {1, 6, 130}) {
    for (int nvec : {1, 2, 3, 7}) {
      SCOPED_TRACE(::testing::Message() << "length " << length << ", " << nvec << " vectors");
      // Linear sums, Z a third array, X or Y.
      for (double a : coefficients)
        for (double b : coefficients)
          for (int alias = 0; alias < 3; ++alias) {
            ++seed;
            Arrays ours(ctx, length, 3, nvec, seed), theirs(ctx, length, 3, nvec, seed);
            const int z = alias == 0 ? 2 : alias - 1;
            ASSERT_EQ(detail::linear_sum_vector_array(nvec, a, ours.arrays[0], b, ours.arrays[1],
                                                      ours.arrays[z]),
                      0);
            ASSERT_EQ(N_VLinearSumVectorArray_Serial(nvec, a, theirs.arrays[0], b, theirs.arrays[1],
                                                     theirs.arrays[z]),
                      0);
            EXPECT_EQ(ours.contents(), theirs.contents()) << "a " << a << ", b " << b;
          }
      // Scales (in place and not), constants, weighted norms.
      for (bool in_place : {false, true}) {
        ++seed;
        Arrays ours(ctx, length, 2, nvec, seed), theirs(ctx, length, 2, nvec, seed);
        std::vector<double> c(nvec);
        for (int i = 0; i < nvec; ++i) c[i] = coefficients[i % 6];
        ASSERT_EQ(detail::scale_vector_array(nvec, c.data(), ours.arrays[0],
                                             ours.arrays[in_place ? 0 : 1]),
                  0);
        ASSERT_EQ(N_VScaleVectorArray_Serial(nvec, c.data(), theirs.arrays[0],
                                             theirs.arrays[in_place ? 0 : 1]),
                  0);
        EXPECT_EQ(ours.contents(), theirs.contents());
      }
      {
        ++seed;
        Arrays ours(ctx, length, 2, nvec, seed), theirs(ctx, length, 2, nvec, seed);
        std::vector<double> mine(nvec), sundials(nvec);
        ASSERT_EQ(detail::weighted_rms_norm_vector_array(nvec, ours.arrays[0], ours.arrays[1],
                                                         mine.data()),
                  0);
        ASSERT_EQ(N_VWrmsNormVectorArray_Serial(nvec, theirs.arrays[0], theirs.arrays[1],
                                                sundials.data()),
                  0);
        EXPECT_EQ(mine, sundials);
        ASSERT_EQ(detail::constant_vector_array(nvec, 0.25, ours.arrays[0]), 0);
        ASSERT_EQ(N_VConstVectorArray_Serial(nvec, 0.25, theirs.arrays[0]), 0);
        detail::set_constant(-3.0, ours.arrays[1][0]);
        N_VConst_Serial(-3.0, theirs.arrays[1][0]);
        EXPECT_EQ(ours.contents(), theirs.contents());
      }
      for (int nsum : {1, 2, 3, 5, 9, 17}) {
        SCOPED_TRACE(::testing::Message() << nsum << " sums");
        std::vector<double> a(nsum);
        for (int j = 0; j < nsum; ++j) a[j] = coefficients[(j + nvec) % 6];
        // Scaled additions: X, then nsum arrays Y and nsum arrays Z (or Z = Y).
        for (bool in_place : {false, true}) {
          ++seed;
          Arrays ours(ctx, length, 1 + 2 * nsum, nvec, seed);
          Arrays theirs(ctx, length, 1 + 2 * nsum, nvec, seed);
          auto y = [&](Arrays& s) { return s.arrays.data() + 1; };
          auto z = [&](Arrays& s) { return in_place ? y(s) : s.arrays.data() + 1 + nsum; };
          ASSERT_EQ(detail::scale_add_multi_vector_array(nvec, nsum, a.data(), ours.arrays[0],
                                                         y(ours), z(ours)),
                    0);
          ASSERT_EQ(N_VScaleAddMultiVectorArray_Serial(nvec, nsum, a.data(), theirs.arrays[0],
                                                       y(theirs), z(theirs)),
                    0);
          EXPECT_EQ(ours.contents(), theirs.contents()) << (in_place ? "in place" : "");
          if (nvec == 1) {  // the single-vector form: x into the nsum vectors Y (or Z)
            std::vector<N_Vector> my(nsum), mz(nsum), ty(nsum), tz(nsum);
            for (int j = 0; j < nsum; ++j) {
              my[j] = y(ours)[j][0];
              mz[j] = z(ours)[j][0];
              ty[j] = y(theirs)[j][0];
              tz[j] = z(theirs)[j][0];
            }
            ASSERT_EQ(
                detail::scale_add_multi(nsum, a.data(), ours.arrays[0][0], my.data(), mz.data()),
                0);
            ASSERT_EQ(
                N_VScaleAddMulti_Serial(nsum, a.data(), theirs.arrays[0][0], ty.data(), tz.data()),
                0);
            EXPECT_EQ(ours.contents(), theirs.contents());
          }
        }
        // Linear combinations: nsum arrays X and Z (a further array, or X[0] with c[0] = 1 or not).
        for (int alias = 0; alias < 3; ++alias) {
          ++seed;
          Arrays ours(ctx, length, nsum + 1, nvec, seed), theirs(ctx, length, nsum + 1, nvec, seed);
          std::vector<double> c = a;
          if (alias == 1) c[0] = 1.0;
          if (alias == 2 && c[0] == 1.0) c[0] = 0.5;
          const int z = alias == 0 ? nsum : 0;
          ASSERT_EQ(detail::linear_combination_vector_array(nvec, nsum, c.data(),
                                                            ours.arrays.data(), ours.arrays[z]),
                    0);
          ASSERT_EQ(N_VLinearCombinationVectorArray_Serial(nvec, nsum, c.data(),
                                                           theirs.arrays.data(), theirs.arrays[z]),
                    0);
          EXPECT_EQ(ours.contents(), theirs.contents()) << "aliasing " << alias;
        }
      }
    }
  }
  SUNContext_Free(&ctx);
}

// A vector given the project's operations passes them on to its clones (the integrators' own
// vectors are clones of the one they are given).
TEST(VectorOps, ClonesInheritTheOperation) {
  SUNContext ctx;
  ASSERT_EQ(SUNContext_Create(nullptr, &ctx), 0);
  N_Vector y = N_VNew_Serial(4, ctx);
  ASSERT_EQ(N_VEnableFusedOps_Serial(y, SUNTRUE), 0);
  detail::use_project_vector_ops(y);
  N_Vector clone = N_VClone(y);
  EXPECT_EQ(clone->ops->nvlinearcombination, &detail::linear_combination);
  EXPECT_EQ(clone->ops->nvscale, &detail::scale);
  EXPECT_EQ(clone->ops->nvwrmsnorm, &detail::weighted_rms_norm);
  EXPECT_EQ(clone->ops->nvlinearsum, &detail::linear_sum);
  EXPECT_EQ(clone->ops->nvabs, &detail::absolute);
  EXPECT_EQ(clone->ops->nvinv, &detail::inverse);
  EXPECT_EQ(clone->ops->nvaddconst, &detail::add_constant);
  EXPECT_EQ(clone->ops->nvconst, &detail::set_constant);
  EXPECT_EQ(clone->ops->nvscaleaddmulti, &detail::scale_add_multi);
  EXPECT_EQ(clone->ops->nvlinearsumvectorarray, &detail::linear_sum_vector_array);
  EXPECT_EQ(clone->ops->nvscalevectorarray, &detail::scale_vector_array);
  EXPECT_EQ(clone->ops->nvconstvectorarray, &detail::constant_vector_array);
  EXPECT_EQ(clone->ops->nvwrmsnormvectorarray, &detail::weighted_rms_norm_vector_array);
  EXPECT_EQ(clone->ops->nvscaleaddmultivectorarray, &detail::scale_add_multi_vector_array);
  EXPECT_EQ(clone->ops->nvlinearcombinationvectorarray, &detail::linear_combination_vector_array);
  N_VDestroy(clone);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
}

}  // namespace
}  // namespace sympathy
