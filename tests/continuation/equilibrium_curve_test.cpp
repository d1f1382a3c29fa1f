// Fold and Hopf curves of equilibria in two parameters (equilibrium_curve.hpp), each against its
// closed form: the cusp's folds 27 b1^2 = 4 b2^3, the Bogdanov-Takens normal form's fold
// b1 = b2^2 / 4 and Hopf line b1 = 0 (omega^2 = -b2, a neutral saddle for b2 > 0), Lorenz's Hopf
// curve rho_H(sigma) = sigma (sigma + beta + 3) / (sigma - beta - 1), and the Bautin normal form's
// generalized Hopf point.
#include "sympathy/continuation/equilibrium_curve.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "cases/bench/hand_written_systems.hpp"
#include "continuation/jacobian_derivatives.hpp"
#include "sympathy/continuation/generalized_hopf.hpp"
#include "sympathy/core/autodiff_system.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

// x' = b1 + b2 x - x^3, y' = -y: folds where b2 = 3 x^2, b1 = -2 x^3 (27 b1^2 = 4 b2^3), the cusp
// at the origin.
class Cusp final : public AutoDiffSystem<Cusp> {
 public:
  Cusp() { set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {-1.0, 1.0}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = p[0] + p[1] * z[0] - z[0] * z[0] * z[0];
    dz[1] = -z[1];
  }
};

// The Bautin normal form in Cartesian coordinates: r' = r (mu + beta r^2 - r^4), theta' = 1. Its
// Hopf points lie on mu = 0, with l1 proportional to beta: generalized Hopf at beta = 0.
class Bautin final : public AutoDiffSystem<Bautin> {
 public:
  Bautin() { set_parameter_layout({{"mu", {0}}, {"beta", {1}}}, {-0.5, -1.0}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    const T g = p[0] + p[1] * r2 - r2 * r2;
    dz[0] = g * z[0] - z[1];
    dz[1] = g * z[1] + z[0];
  }
};

// The normal forms above turned and bent, so that no eigenvector is a coordinate axis and f has
// quadratic terms the normal form does not: z = R phi(w), R the rotation by 0.6 rad, phi(w) =
// w + Q(w) with Q(w) = (0.3 w0 w1 - 0.2 w1^2, 0.25 w0^2 + 0.1 w0 w1), a near-identity change of
// coordinates; z' = R Dphi(w) g(w) with w = phi^-1(R^T z) (a fixed-point iteration, converged to
// rounding for |w| < 1). Conjugate to g: the same curves in the parameters, and the same
// normal-form coefficients in MatCont's normalisation (|q0| = 1 is kept by R, and phi's linear
// part is the identity).
template <class Normal>
class Bent final : public AutoDiffSystem<Bent<Normal>> {
 public:
  Bent() { this->set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {0.0, 0.0}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"z0", "z1"}; }
  static Eigen::Vector2d forward(const Eigen::Vector2d& w) {
    const Eigen::Vector2d bent(w[0] + 0.3 * w[0] * w[1] - 0.2 * w[1] * w[1],
                               w[1] + 0.25 * w[0] * w[0] + 0.1 * w[0] * w[1]);
    return {kCos * bent[0] - kSin * bent[1], kSin * bent[0] + kCos * bent[1]};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T u0 = kCos * z[0] + kSin * z[1], u1 = -kSin * z[0] + kCos * z[1];
    T w0 = u0, w1 = u1;
    for (int k = 0; k < 80; ++k) {
      const T n0 = u0 - (0.3 * w0 * w1 - 0.2 * w1 * w1);
      const T n1 = u1 - (0.25 * w0 * w0 + 0.1 * w0 * w1);
      w0 = n0;
      w1 = n1;
    }
    T g[2];
    Normal::field(w0, w1, p, g);
    const T d0 = (1.0 + 0.3 * w1) * g[0] + (0.3 * w0 - 0.4 * w1) * g[1];
    const T d1 = (0.5 * w0 + 0.1 * w1) * g[0] + (1.0 + 0.1 * w0) * g[1];
    dz[0] = kCos * d0 - kSin * d1;
    dz[1] = kSin * d0 + kCos * d1;
  }

 private:
  static constexpr double kCos = 0.82533561490967829724;  // cos 0.6
  static constexpr double kSin = 0.56464247339503535720;  // sin 0.6
};

// w0' = w1, w1' = b1 + b2 w0 + w0^2 - w0 w1: a = 1, b = -1 in MatCont's normalisation at the
// origin (q0 = (1, 0), q1 = (0, 1), p0 = (1, 0), p1 = (0, 1)).
struct BogdanovTakensField {
  template <class T, class P>
  static void field(const T& w0, const T& w1, const P* p, T* g) {
    g[0] = w1;
    g[1] = p[0] + p[1] * w0 + w0 * w0 - w0 * w1;
  }
};
// w0' = b1 + b2 w0 - w0^3, w1' = -w1: c = -1 (q = p = (1, 0), C(q, q, q) = -6).
struct CuspField {
  template <class T, class P>
  static void field(const T& w0, const T& w1, const P* p, T* g) {
    g[0] = p[0] + p[1] * w0 - w0 * w0 * w0;
    g[1] = -w1;
  }
};

// The Bautin normal form as a field of w: r' = r (b1 + b2 r^2 - r^4), theta' = 1 + r^2 / 2. With
// |q| = 1, q = (1, -i) / sqrt 2, so r^2 = 2 |z|^2 and z' = (b1 + i) z + (2 b2 + i) z |z|^2 -
// 4 z |z|^4: at the generalized Hopf point b1 = b2 = 0, l1 = 2 b2 = 0 and l2 = Re c2 / omega = -4.
// (c1's imaginary part is not zero, so that the terms of l2's formula with it count.)
struct BautinField {
  template <class T, class P>
  static void field(const T& w0, const T& w1, const P* p, T* g) {
    const T r2 = w0 * w0 + w1 * w1;
    const T a = p[0] + p[1] * r2 - r2 * r2;
    const T turn = 1.0 + 0.5 * r2;
    g[0] = a * w0 - turn * w1;
    g[1] = a * w1 + turn * w0;
  }
};

// A Hopf pair beside a third eigenvalue. FoldHopf (Kuznetsov's normal form, theta = 1):
// z' = b1 + z^2, (x, y) a Hopf pair with mu = b2 + z and omega = 1: equilibria (0, 0, z) with
// z^2 = -b1, Hopf where b2 = -z, so the Hopf curve is b1 = -b2^2, the real eigenvalue 2 z = -2 b2
// passing zero at the zero-Hopf point b1 = b2 = 0. TranscriticalHopf: the pair with mu = b1 and
// z' = b2 z - z^2, whose equilibria cross at b2 = 0 (AUTO's pp3 has such a point): the Hopf curve
// b1 = 0 has a zero-Hopf point at b2 = 0 where its augmented system is singular (the equilibria's
// branch point). DoubleHopf: (u, v) a second pair with mu = b2 and omega = sqrt 2 beside the
// first with mu = b1: the Hopf curve b1 = 0 meets the second pair's at b2 = 0.
class TwoCrossings final : public AutoDiffSystem<TwoCrossings> {
 public:
  enum class Kind { FoldHopf, TranscriticalHopf, DoubleHopf };
  Kind kind() const { return kind_; }
  explicit TwoCrossings(Kind kind) : kind_(kind) {
    set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {-0.5, -0.5});
  }
  int dimension() const override { return kind_ == Kind::DoubleHopf ? 4 : 3; }
  std::vector<std::string> state_names() const override {
    return kind_ == Kind::DoubleHopf ? std::vector<std::string>{"x", "y", "u", "v"}
                                     : std::vector<std::string>{"x", "y", "z"};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    const T mu = kind_ == Kind::FoldHopf ? T(p[1] + z[2]) : T(p[0]);
    dz[0] = mu * z[0] - z[1] - z[0] * r2;
    dz[1] = z[0] + mu * z[1] - z[1] * r2;
    if (kind_ == Kind::FoldHopf) {
      dz[2] = p[0] + z[2] * z[2];
      return;
    }
    if (kind_ == Kind::TranscriticalHopf) {
      dz[2] = p[1] * z[2] - z[2] * z[2];
      return;
    }
    const double w = std::sqrt(2.0);
    const T s2 = z[2] * z[2] + z[3] * z[3];
    dz[2] = p[1] * z[2] - w * z[3] - z[2] * s2;
    dz[3] = w * z[2] + p[1] * z[3] - z[3] * s2;
  }

 private:
  Kind kind_;
};

// A field of w in N dimensions turned and bent, as Bent does in two: z = R (w + Q(w)) with
// Q_i(w) = 0.2 w_i w_(i+1) + 0.15 w_(i+1)^2 - 0.1 w_i w_(i+2) (indices mod N) and R the product
// of rotations by 0.6, 0.5, ... rad in the planes (0, 1), (1, 2), ...; z' = R (I + DQ(w)) g(w),
// DQ(w) g = Q(w + g) - Q(w) - Q(g), w from z by a fixed-point iteration. Its normal-form
// coefficients are g's: R keeps |q| = 1 and Q has no linear part. (A Q with only w_i w_(i+1)
// left B(q0, conj q0) of a pair in the plane (0, 1) zero, and the terms with it untested.)
template <class Field, int N>
class Warped final : public AutoDiffSystem<Warped<Field, N>> {
 public:
  Warped() { this->set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {-0.5, -0.5}); }
  int dimension() const override { return N; }
  std::vector<std::string> state_names() const override {
    std::vector<std::string> names;
    for (int i = 0; i < N; ++i) names.push_back(std::string(1, 'z').append(std::to_string(i)));
    return names;
  }
  template <class T>
  static void rotate(T* v, bool inverse) {
    for (int m = 0; m < N - 1; ++m) {
      const int k = inverse ? N - 2 - m : m;
      const double angle = (inverse ? -1.0 : 1.0) * (0.6 - 0.1 * k);
      const double c = std::cos(angle), s = std::sin(angle);
      const T a = v[k], b = v[k + 1];
      v[k] = c * a - s * b;
      v[k + 1] = s * a + c * b;
    }
  }
  template <class T>
  static void bend(const T* w, T* q) {
    for (int i = 0; i < N; ++i) {
      const T& a = w[i];
      const T& b = w[(i + 1) % N];
      const T& c = w[(i + 2) % N];
      q[i] = 0.2 * a * b + 0.15 * b * b - 0.1 * a * c;
    }
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    T u[N], w[N], g[N], sum[N], qw[N], qg[N], qs[N];
    for (int i = 0; i < N; ++i) u[i] = z[i];
    rotate(u, true);
    for (int i = 0; i < N; ++i) w[i] = u[i];
    for (int it = 0; it < 150; ++it) {
      bend(w, qw);
      for (int i = 0; i < N; ++i) w[i] = u[i] - qw[i];
    }
    Field::field(w, p, g);
    for (int i = 0; i < N; ++i) sum[i] = w[i] + g[i];
    bend(w, qw);
    bend(g, qg);
    bend(sum, qs);
    for (int i = 0; i < N; ++i) dz[i] = g[i] + qs[i] - qw[i] - qg[i];
    rotate(dz, false);
  }
};

// A fold-Hopf normal form, w = (z, x, y): z' = b1 + z^2 - r2, the pair with mu = b2 + 0.8 z and
// omega 1, r2 = x^2 + y^2. ZH at the origin with b = 1, c = <p0, B(q1, conj q1)> = -2 (|q1| = 1:
// B's z-part 2 (-1) |q1|^2), a = 0.8: s = -1, theta = 0.4 (b, c, a flip with q0's sign).
struct ZeroHopfField {
  template <class T, class P>
  static void field(const T* w, const P* p, T* g) {
    const T r2 = w[1] * w[1] + w[2] * w[2];
    const T mu = p[1] + 0.8 * w[0];
    g[0] = p[0] + w[0] * w[0] - r2;
    g[1] = mu * w[1] - w[2] - w[1] * r2;
    g[2] = w[1] + mu * w[2] - w[2] * r2;
  }
};
// Two pairs, w = (x, y, u, v), omega 1 and sqrt 2, with mu = b1 and b2 and the amplitudes'
// cubic coupling P = [[-1, -0.5], [0.7, -2]] in r1 = x^2 + y^2, r2 = u^2 + v^2. With |q| = 1,
// r = 2 |w|^2: p11 = -2, p12 = -1, p21 = 1.4, p22 = -4, theta = 0.25, delta = -0.7.
struct DoubleHopfField {
  template <class T, class P>
  static void field(const T* w, const P* p, T* g) {
    const T r1 = w[0] * w[0] + w[1] * w[1], r2 = w[2] * w[2] + w[3] * w[3];
    const T f = -1.0 * r1 - 0.5 * r2, h = 0.7 * r1 - 2.0 * r2;
    const double omega = std::sqrt(2.0);
    g[0] = p[0] * w[0] - w[1] + w[0] * f;
    g[1] = w[0] + p[0] * w[1] + w[1] * f;
    g[2] = p[1] * w[2] - omega * w[3] + w[2] * h;
    g[3] = omega * w[2] + p[1] * w[3] + w[3] * h;
  }
};

EquilibriumBranch branch_of(const OdeSystem& system, int parameter, double from, double to,
                            Eigen::VectorXd start) {
  EquilibriumProblem p;
  p.parameter = parameter;
  p.values = system.default_parameters();
  p.from = from;
  p.to = to;
  p.start_state = std::move(start);
  return continue_equilibria(system, p, {});
}

const EquilibriumEvent& first_of(const EquilibriumBranch& b, EquilibriumEventType type) {
  for (const auto& e : b.events)
    if (e.type == type) return e;
  throw std::runtime_error("no such event");
}

EquilibriumCurveOptions window(double a0, double a1, double b0, double b1) {
  EquilibriumCurveOptions o;
  o.first_lower = a0;
  o.first_upper = a1;
  o.second_lower = b0;
  o.second_upper = b1;
  return o;
}

std::vector<EquilibriumCurveEvent> events_named(const EquilibriumCurve& c, const std::string& t) {
  std::vector<EquilibriumCurveEvent> out;
  for (const auto& e : c.events)
    if (e.type == t) out.push_back(e);
  return out;
}

// The cusp's fold curve from the fold at b2 = 1: every point on 27 b1^2 = 4 b2^3 with b2 = 3 x^2
// (1e-9), through the cusp point at the origin (located to 1e-8), both halves to b2 = 2.
TEST(EquilibriumCurve, CuspFoldsOnTheirClosedFormAndTheCuspPoint) {
  const Cusp system;
  const auto branch = branch_of(system, 0, -1.0, 1.0, Eigen::Vector2d(-1.3247, 0.0));
  const auto& lp = first_of(branch, EquilibriumEventType::Fold);
  const auto curve = continue_equilibrium_curve(system, branch, lp, 1, window(-2, 2, -0.5, 2));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  EXPECT_EQ(curve.stop, StopReason::ParameterBound) << curve.stop_reason;
  for (const auto& p : curve.points) {
    const double x = p.state[0];
    EXPECT_NEAR(p.second, 3 * x * x, 1e-9) << p.index;
    EXPECT_NEAR(p.first, -2 * x * x * x, 1e-9) << p.index;
  }
  EXPECT_NEAR(curve.points.front().second, 2.0, 1e-12);
  EXPECT_NEAR(curve.points.back().second, 2.0, 1e-12);
  const auto cusps = events_named(curve, "CP");
  ASSERT_EQ(cusps.size(), 1u) << curve.events.size();
  EXPECT_TRUE(cusps[0].located) << cusps[0].note;
  EXPECT_NEAR(cusps[0].first, 0.0, 1e-8);
  EXPECT_NEAR(cusps[0].second, 0.0, 1e-8);
  EXPECT_TRUE(events_named(curve, "BT").empty());
}

// The Bogdanov-Takens normal form: its Hopf line b1 = 0 with omega^2 = -b2, through the BT point
// at the origin (1e-8) into neutral saddles (kappa = -b2 < 0, labelled); its fold curve
// b1 = b2^2 / 4 through the same BT point. Each point to 1e-9.
TEST(EquilibriumCurve, BogdanovTakensHopfAndFoldCurvesMeetAtTheOrigin) {
  const testing::BogdanovTakens system;
  // At b2 = -1: equilibria x^2 - x + b1 = 0; the one near x = 0.11 at b1 = 0.1 has its Hopf point
  // at b1 = 0 (x = 0) and meets the other at the fold b1 = 1/4 (x = 1/2).
  const auto branch = branch_of(system, 0, 0.1, -0.1, Eigen::Vector2d(0.1127, 0.0));
  const auto hopf = continue_equilibrium_curve(
      system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(-1, 1, -1.5, 1));
  ASSERT_TRUE(hopf.started()) << hopf.stop_reason;
  for (const auto& p : hopf.points) {
    EXPECT_NEAR(p.first, 0.0, 1e-9) << p.index;
    EXPECT_NEAR(p.kappa, -p.second, 1e-9) << p.index;
    EXPECT_EQ(p.neutral_saddle, p.second > 0) << p.index;
  }
  const auto bt = events_named(hopf, "BT");
  ASSERT_EQ(bt.size(), 1u);
  EXPECT_TRUE(bt[0].located);
  EXPECT_NEAR(bt[0].second, 0.0, 1e-8);
  EXPECT_NEAR(bt[0].first, 0.0, 1e-8);

  const auto up = branch_of(system, 0, 0.1, 0.3, Eigen::Vector2d(0.1127, 0.0));
  const auto fold = continue_equilibrium_curve(system, up, first_of(up, EquilibriumEventType::Fold),
                                               1, window(-1, 1, -1.5, 1));
  ASSERT_TRUE(fold.started()) << fold.stop_reason;
  for (const auto& p : fold.points) {
    EXPECT_NEAR(p.first, p.second * p.second / 4, 1e-9) << p.index;
    EXPECT_NEAR(p.state[0], -p.second / 2, 1e-9) << p.index;
  }
  const auto bt_fold = events_named(fold, "BT");
  ASSERT_EQ(bt_fold.size(), 1u);
  EXPECT_NEAR(bt_fold[0].second, 0.0, 1e-8);
}

// Lorenz's Hopf curve in (rho, sigma) at beta = 8/3: rho_H = sigma (sigma + beta + 3) /
// (sigma - beta - 1), each point to 1e-9 relative, omega^2 = kappa positive throughout.
TEST(EquilibriumCurve, LorenzHopfCurveIsTheClosedForm) {
  const bench::HandLorenz system;
  const double beta = 8.0 / 3.0, rho = 30.0;
  const double x = std::sqrt(beta * (rho - 1));
  const auto branch = branch_of(system, 0, 30, 2, Eigen::Vector3d(x, x, rho - 1));
  const auto curve = continue_equilibrium_curve(
      system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(0, 200, 6, 20));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  EXPECT_GT(curve.points.size(), 10u);
  for (const auto& p : curve.points) {
    const double s = p.second;
    EXPECT_NEAR(p.first, s * (s + beta + 3) / (s - beta - 1), 1e-9 * p.first) << p.index;
    EXPECT_GT(p.kappa, 0.0);
  }
  EXPECT_NEAR(curve.points.front().second, 6.0, 1e-12);
  EXPECT_NEAR(curve.points.back().second, 20.0, 1e-12);
}

// The Bautin normal form's Hopf line mu = 0: l1 changes sign with beta, the generalized Hopf point
// at beta = 0 (1e-8).
TEST(EquilibriumCurve, BautinGeneralizedHopfPoint) {
  const Bautin system;
  const auto branch = branch_of(system, 0, -0.5, 0.5, Eigen::Vector2d(0.0, 0.0));
  const auto curve = continue_equilibrium_curve(
      system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(-1, 1, -1, 1));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  for (const auto& p : curve.points) EXPECT_NEAR(p.first, 0.0, 1e-10) << p.index;
  const auto gh = events_named(curve, "GH");
  ASSERT_EQ(gh.size(), 1u);
  EXPECT_TRUE(gh[0].located) << gh[0].note;
  EXPECT_NEAR(gh[0].second, 0.0, 1e-8);
}

// The bent Bogdanov-Takens normal form: its Hopf line and fold parabola as before (1e-9), the BT
// point at the origin on both, with a = 1 and b = -1 (1e-6 relative; measured 3e-11; q0's sign
// fixed by its largest component, as the coefficients flip with it).
TEST(EquilibriumCurve, BentBogdanovTakensCoefficients) {
  const Bent<BogdanovTakensField> system;
  ParameterValues p = system.default_parameters();
  // At b2 = -1 the equilibrium w = (0.1127, 0) at b1 = 0.1, bent.
  EquilibriumProblem problem;
  problem.parameter = 0;
  problem.values = system.with_parameter(p, 1, -1.0);
  problem.from = 0.1;
  problem.to = -0.1;
  problem.start_state = Bent<BogdanovTakensField>::forward({0.1127016653792583, 0.0});
  const auto branch = continue_equilibria(system, problem, {});
  const auto hopf = continue_equilibrium_curve(
      system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(-1, 1, -1.5, 1));
  ASSERT_TRUE(hopf.started()) << hopf.stop_reason;
  for (const auto& pt : hopf.points) EXPECT_NEAR(pt.first, 0.0, 1e-9) << pt.index;
  const auto bt = events_named(hopf, "BT");
  ASSERT_EQ(bt.size(), 1u);
  EXPECT_NEAR(bt[0].second, 0.0, 1e-8);
  ASSERT_EQ(bt[0].coefficients.size(), 2u) << bt[0].note;
  EXPECT_NEAR(bt[0].coefficients[0].second, 1.0, 1e-6) << bt[0].note;
  EXPECT_NEAR(bt[0].coefficients[1].second, -1.0, 1e-6) << bt[0].note;

  problem.to = 0.3;
  const auto up = continue_equilibria(system, problem, {});
  const auto fold = continue_equilibrium_curve(system, up, first_of(up, EquilibriumEventType::Fold),
                                               1, window(-1, 1, -1.5, 1));
  ASSERT_TRUE(fold.started()) << fold.stop_reason;
  for (const auto& pt : fold.points)
    EXPECT_NEAR(pt.first, pt.second * pt.second / 4, 1e-9) << pt.index;
  const auto bt_fold = events_named(fold, "BT");
  ASSERT_EQ(bt_fold.size(), 1u);
  ASSERT_EQ(bt_fold[0].coefficients.size(), 2u);
  EXPECT_NEAR(bt_fold[0].coefficients[0].second, 1.0, 1e-6);
  EXPECT_NEAR(bt_fold[0].coefficients[1].second, -1.0, 1e-6);
}

// The bent cusp: its folds on 27 b1^2 = 4 b2^3 (1e-9) and the cusp point with c = -1 (1e-6;
// measured 2e-10).
TEST(EquilibriumCurve, BentCuspCoefficient) {
  const Bent<CuspField> system;
  EquilibriumProblem problem;
  problem.parameter = 0;
  problem.values = system.with_parameter(system.default_parameters(), 1, 0.5);
  problem.from = -1.0;
  problem.to = 1.0;
  // w0^3 - 0.5 w0 + 1 = 0 at b1 = -1: w0 = -1.1915.
  problem.start_state = Bent<CuspField>::forward({-1.1914878, 0.0});
  const auto branch = continue_equilibria(system, problem, {});
  const auto curve = continue_equilibrium_curve(
      system, branch, first_of(branch, EquilibriumEventType::Fold), 1, window(-2, 2, -0.3, 0.6));
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  for (const auto& pt : curve.points)
    EXPECT_NEAR(27 * pt.first * pt.first, 4 * pt.second * pt.second * pt.second, 1e-9) << pt.index;
  const auto cusps = events_named(curve, "CP");
  ASSERT_EQ(cusps.size(), 1u);
  EXPECT_NEAR(cusps[0].second, 0.0, 1e-8);
  ASSERT_EQ(cusps[0].coefficients.size(), 1u) << cusps[0].note;
  EXPECT_NEAR(cusps[0].coefficients[0].second, -1.0, 1e-6);
}

// The bent Bautin form's Hopf curve in b2 from the Hopf point of its equilibria in b1 at b2 = -1.
EquilibriumCurve bautin_hopf_curve(const Bent<BautinField>& system) {
  EquilibriumProblem problem;
  problem.parameter = 0;
  problem.values = system.with_parameter(system.default_parameters(), 1, -1.0);
  problem.from = -0.5;
  problem.to = 0.5;
  problem.start_state = Eigen::Vector2d::Zero();
  const auto branch = continue_equilibria(system, problem, {});
  return continue_equilibrium_curve(system, branch, first_of(branch, EquilibriumEventType::Hopf), 1,
                                    window(-1, 1, -1, 1));
}

// The bent Bautin normal form: its Hopf curve b1 = 0 (1e-9), the generalized Hopf point at b2 = 0
// (1e-8) with l2 = -4 (1e-6 relative; a wrong factor of h31's g21 term gives -4.0425), from f's
// fourth and fifth derivatives on Taylor jets.
TEST(EquilibriumCurve, BentBautinSecondLyapunovCoefficient) {
  const Bent<BautinField> system;
  const auto curve = bautin_hopf_curve(system);
  ASSERT_TRUE(curve.started()) << curve.stop_reason;
  for (const auto& pt : curve.points) EXPECT_NEAR(pt.first, 0.0, 1e-9) << pt.index;
  const auto gh = events_named(curve, "GH");
  ASSERT_EQ(gh.size(), 1u);
  EXPECT_NEAR(gh[0].second, 0.0, 1e-8);
  ASSERT_EQ(gh[0].coefficients.size(), 1u) << gh[0].note;
  EXPECT_EQ(gh[0].coefficients[0].first, "l2");
  EXPECT_NEAR(gh[0].coefficients[0].second, -4.0, 4e-6) << gh[0].note;  // measured 1e-15
  // l1 on the curve: 2 b2 (1e-8).
  for (const auto& pt : curve.points) {
    if (pt.kappa > 0.0) {
      EXPECT_NEAR(pt.lyapunov, 2 * pt.second, 1e-8) << pt.index;
    }
  }
}

// The fold of cycles born at the bent Bautin normal form's generalized Hopf point: r' = r (b1 +
// b2 r^2 - r^4) turns where b1 = -b2^2 / 4 (b2 > 0, at r^2 = b2 / 2), a relation the bending
// keeps. Every point of the curve on it (1e-8; measured 9e-11), the curve reaching towards GH
// (b2 < 0.05: it ends halfway from its start, b2 = 0.02, where it degenerates) and out to
// b2 = 0.5; and the folds that continue locates
// on the families born at b2 = 0.2 and 0.4 on it within their uncertainties plus 1e-9 (measured
// 1e-13 and 6e-11: a fold's uncertainty counts its bracket, not the corrector's tolerance): the
// curve and the one-parameter folds meet.
TEST(EquilibriumCurve, FoldOfCyclesFromGeneralizedHopf) {
  const Bent<BautinField> system;
  const auto hopf_curve = bautin_hopf_curve(system);
  const auto gh = events_named(hopf_curve, "GH");
  ASSERT_EQ(gh.size(), 1u);
  ASSERT_EQ(gh[0].coefficients.size(), 1u);
  GeneralizedHopfPoint point;
  point.at = codimension_two_point(system, hopf_curve, gh[0]);
  point.l2 = gh[0].coefficients[0].second;
  GeneralizedHopfOptions options;
  options.curve.first_lower = -0.2;
  options.curve.first_upper = 0.05;
  options.curve.second_lower = -0.1;
  options.curve.second_upper = 0.5;
  const auto fold = fold_of_cycles_from_generalized_hopf(system, point, options);
  EXPECT_GT(*fold.hopf.lyapunov, 0.0);  // l2 < 0: the fold where l1 > 0
  ASSERT_TRUE(fold.curve.started()) << fold.curve.stop_reason;
  double lowest = 1.0, highest = 0.0;
  for (const auto& pt : fold.curve.points) {
    EXPECT_NEAR(pt.first, -pt.second * pt.second / 4, 1e-8) << pt.index;
    lowest = std::min(lowest, pt.second);
    highest = std::max(highest, pt.second);
  }
  EXPECT_LT(lowest, 0.05) << fold.curve.stop_reason;
  EXPECT_EQ(fold.curve.backward_stop, StopReason::HopfPoint) << fold.curve.stop_reason;
  EXPECT_NEAR(highest, 0.5, 1e-12) << fold.curve.stop_reason;
  for (double b2 : {0.2, 0.4}) {
    std::string why;
    const auto h = hopf_point_near(system, 0, system.with_parameter(hopf_curve.start_values, 1, b2),
                                   Eigen::Vector2d::Zero(), 1.0, 1e-3, why);
    ASSERT_TRUE(h) << why;
    ContinuationOptions family;
    family.lower = -0.2;
    family.upper = 0.05;
    HopfStartOptions start;
    start.amplitude = 0.05;
    const Branch b = continue_from_hopf(system, 0, *h, family, {}, start);
    const auto lp = std::find_if(b.events.begin(), b.events.end(), [](const Bifurcation& e) {
      return e.type == BifurcationType::Fold && e.located();
    });
    ASSERT_NE(lp, b.events.end()) << b.stop_reason;
    EXPECT_NEAR(lp->parameter, -b2 * b2 / 4, lp->uncertainty + 1e-9) << b2;
  }
}

// The derivative tensors from Taylor jets are symmetric and agree with central differences of
// the lower orders' (step 1e-4: truncation 1e-8, rounding 1e-12 relative), on the bent Bautin
// field away from its equilibrium, complex arguments throughout.
TEST(EquilibriumCurve, DerivativeTensorsAgreeWithDifferences) {
  using C = std::complex<double>;
  const Bent<BautinField> system;
  const ParameterValues p = system.with_parameter(system.default_parameters(), 1, 0.7);
  const Eigen::VectorXd x = Eigen::Vector2d(0.31, -0.22);
  const Eigen::VectorXd y = Eigen::Vector2d(0.6, 0.8);  // the differences' direction, real
  const Eigen::VectorXcd a = Eigen::Vector2cd(C(0.3, 0.5), C(-0.7, 0.1));
  const Eigen::VectorXcd b = Eigen::Vector2cd(C(-0.2, 0.9), C(0.4, -0.3));
  const Eigen::VectorXcd c = Eigen::Vector2cd(C(1.1, 0.0), C(0.0, 0.6));
  const Eigen::VectorXcd d = Eigen::Vector2cd(C(0.5, -0.5), C(0.2, 0.2));
  const detail::JacobianDerivatives at(system, p, x);
  ASSERT_TRUE(at.exact());
  const double h = 1e-4;
  const Eigen::VectorXd up = x + h * y, down = x - h * y;
  const detail::JacobianDerivatives above(system, p, up), below(system, p, down);
  const Eigen::VectorXcd yc = y.cast<C>();
  const auto check = [](const Eigen::VectorXcd& exact, const Eigen::VectorXcd& differenced,
                        const char* what) {
    EXPECT_LT((exact - differenced).norm(), 1e-7 * std::max(1.0, exact.norm())) << what;
  };
  check(*at.form({a, yc}), (*above.form({a}) - *below.form({a})) / (2 * h), "order 2");
  check(*at.form({a, b, yc}), (*above.form({a, b}) - *below.form({a, b})) / (2 * h), "order 3");
  check(*at.form({a, b, c, yc}), (*above.form({a, b, c}) - *below.form({a, b, c})) / (2 * h),
        "order 4");
  check(*at.form({a, b, c, d, yc}),
        (*above.form({a, b, c, d}) - *below.form({a, b, c, d})) / (2 * h), "order 5");
  // Symmetric in its arguments, and complex linear in each.
  const Eigen::VectorXcd abcd = *at.form({a, b, c, d, yc});
  EXPECT_LT((abcd - *at.form({yc, d, c, b, a})).norm(), 1e-13 * abcd.norm());
  EXPECT_LT((C(0, 2) * abcd - *at.form({C(0, 2) * a, b, c, d, yc})).norm(), 1e-13 * abcd.norm());
  // The first order is the Jacobian's product.
  Eigen::MatrixXd jac;
  system.jacobian(0.0, x.data(), p.data(), jac);
  EXPECT_LT((*at.form({a}) - jac.cast<C>() * a).norm(), 1e-14);
}

// The Hopf curve in b2 of a TwoCrossings system from its equilibria in b1 at b2 = -0.5: the
// fold-Hopf's z = sqrt(-b1) has its Hopf point at z = 0.5 (b1 = -0.25); the others' origin at
// b1 = 0.
EquilibriumCurve two_crossings_hopf_curve(const TwoCrossings& system) {
  const bool fold_hopf = system.kind() == TwoCrossings::Kind::FoldHopf;
  Eigen::VectorXd start = Eigen::VectorXd::Zero(system.dimension());
  if (fold_hopf) start[2] = std::sqrt(0.5);
  const auto branch = branch_of(system, 0, -0.5, fold_hopf ? -0.01 : 0.5, start);
  return continue_equilibrium_curve(system, branch, first_of(branch, EquilibriumEventType::Hopf), 1,
                                    window(-1, 1, -0.5, 0.5));
}

// The zero-Hopf point of the fold-Hopf normal form's Hopf curve b1 = -b2^2, the one where the
// equilibria cross (its probe at the singular point tried beside it) and the double Hopf point of
// two pairs, each at b1 = b2 = 0 (1e-8) and the only codimension-two point found; every point on
// the closed form (1e-10).
TEST(EquilibriumCurve, ZeroHopfAndDoubleHopfPoints) {
  using Kind = TwoCrossings::Kind;
  for (const Kind kind : {Kind::FoldHopf, Kind::TranscriticalHopf, Kind::DoubleHopf}) {
    SCOPED_TRACE(static_cast<int>(kind));
    const TwoCrossings system(kind);
    const auto curve = two_crossings_hopf_curve(system);
    ASSERT_TRUE(curve.started()) << curve.stop_reason;
    for (const auto& p : curve.points)
      EXPECT_NEAR(p.first, kind == Kind::FoldHopf ? -p.second * p.second : 0.0, 1e-10) << p.index;
    ASSERT_EQ(curve.events.size(), 1u) << curve.stop_reason;
    EXPECT_EQ(curve.events[0].type, kind == Kind::DoubleHopf ? "HH" : "ZH");
    EXPECT_TRUE(curve.events[0].located) << curve.events[0].note;
    EXPECT_NEAR(curve.events[0].second, 0.0, 1e-8);
    EXPECT_NEAR(curve.events[0].first, 0.0, 1e-8);
  }
}

// The switches at codimension-two points, each new curve on its closed form (1e-9): the
// fold-Hopf form's ZH on its Hopf curve to the fold curve b1 = 0 (z = 0 double); the two Hopf
// pairs' HH to the other pair's Hopf curve b2 = 0 (omega = sqrt 2); the bent BT form's BT from the
// Hopf curve to the fold curve b1 = b2^2 / 4, and a fold curve's BT to the Hopf curve b1 = 0
// (Hopf points for b2 < 0, neutral saddles for b2 > 0). A GH switches to no curve of equilibria.
// (A point a curve starts at is not found on it again: its test is zero there.)
TEST(EquilibriumCurve, SwitchesAtCodimensionTwoPoints) {
  using Kind = TwoCrossings::Kind;
  const auto only = [](const EquilibriumCurve& c, const std::string& type) {
    const auto found = events_named(c, type);
    EXPECT_EQ(found.size(), 1u) << type << ": " << c.stop_reason;
    return found.empty() ? EquilibriumCurveEvent{} : found[0];
  };
  {
    const TwoCrossings system(Kind::FoldHopf);
    const auto hopf = two_crossings_hopf_curve(system);
    const auto fold = continue_from_codimension_two(
        system, codimension_two_point(system, hopf, only(hopf, "ZH")), window(-1, 1, -0.5, 0.5));
    ASSERT_TRUE(fold.started()) << fold.stop_reason;
    EXPECT_EQ(fold.kind, EquilibriumEventType::Fold);
    EXPECT_GT(fold.points.size(), 5u);
    for (const auto& p : fold.points) EXPECT_NEAR(p.first, 0.0, 1e-9) << p.index;
  }
  {
    const TwoCrossings system(Kind::DoubleHopf);
    const auto hopf = two_crossings_hopf_curve(system);
    const auto other = continue_from_codimension_two(
        system, codimension_two_point(system, hopf, only(hopf, "HH")), window(-1, 1, -0.5, 0.5));
    ASSERT_TRUE(other.started()) << other.stop_reason;
    EXPECT_EQ(other.kind, EquilibriumEventType::Hopf);
    EXPECT_GT(other.points.size(), 5u);
    for (const auto& p : other.points) {
      EXPECT_NEAR(p.second, 0.0, 1e-9) << p.index;
      EXPECT_NEAR(p.kappa, 2.0, 1e-9) << p.index;
    }
  }
  {
    const Bent<BogdanovTakensField> system;
    EquilibriumProblem problem;
    problem.parameter = 0;
    problem.values = system.with_parameter(system.default_parameters(), 1, -1.0);
    problem.from = 0.1;
    problem.to = -0.1;
    problem.start_state = Bent<BogdanovTakensField>::forward({0.1127016653792583, 0.0});
    const auto branch = continue_equilibria(system, problem, {});
    const auto hopf = continue_equilibrium_curve(
        system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(-1, 1, -1.5, 1));
    const auto fold = continue_from_codimension_two(
        system, codimension_two_point(system, hopf, only(hopf, "BT")), window(-1, 1, -1.5, 1));
    ASSERT_TRUE(fold.started()) << fold.stop_reason;
    EXPECT_EQ(fold.kind, EquilibriumEventType::Fold);
    EXPECT_GT(fold.points.size(), 5u);
    for (const auto& p : fold.points)
      EXPECT_NEAR(p.first, p.second * p.second / 4, 1e-9) << p.index;
    // The fold curve from the equilibria's own fold (its BT is not at its start), and its BT.
    problem.to = 0.3;
    const auto up = continue_equilibria(system, problem, {});
    const auto fold_from_lp = continue_equilibrium_curve(
        system, up, first_of(up, EquilibriumEventType::Fold), 1, window(-1, 1, -1.5, 1));
    const auto back = continue_from_codimension_two(
        system, codimension_two_point(system, fold_from_lp, only(fold_from_lp, "BT")),
        window(-1, 1, -1.5, 1));
    ASSERT_TRUE(back.started()) << back.stop_reason;
    EXPECT_EQ(back.kind, EquilibriumEventType::Hopf);
    int hopf_points = 0, saddles = 0;
    for (const auto& p : back.points) {
      EXPECT_NEAR(p.first, 0.0, 1e-9) << p.index;
      if (p.second < -1e-3) hopf_points += p.kappa > 0.0 && !p.neutral_saddle;
      if (p.second > 1e-3) saddles += p.neutral_saddle;
    }
    EXPECT_GT(hopf_points, 3);
    EXPECT_GT(saddles, 3);
    auto gh = codimension_two_point(system, hopf, only(hopf, "BT"));
    gh.type = "GH";
    EXPECT_THROW(continue_from_codimension_two(system, gh, window(-1, 1, -1.5, 1)),
                 std::invalid_argument);
  }
}

// The zero-Hopf and double Hopf coefficients on the turned and bent normal forms above (1e-6
// relative): ZH's sign-free b c = -2, a / b = 0.8, s = -1, theta = 0.4; HH's p11 = -2, p12 = -1,
// p21 = 1.4, p22 = -4, theta = 0.25, delta = -0.7.
TEST(EquilibriumCurve, WarpedZeroHopfAndDoubleHopfCoefficients) {
  const auto coefficient = [](const EquilibriumCurveEvent& e, const std::string& name) {
    for (const auto& [key, value] : e.coefficients)
      if (key == name) return value;
    ADD_FAILURE() << name << " missing: " << e.note;
    return std::nan("");
  };
  {
    const Warped<ZeroHopfField, 3> system;
    // Equilibria z = sqrt(-b1) at b2 = -0.5: the Hopf point where b2 + 0.8 z = 0, z = 0.625.
    Eigen::VectorXd start = Eigen::VectorXd::Zero(3);
    start[0] = 0.8;
    Warped<ZeroHopfField, 3>::rotate(start.data(), false);  // Q(w) = 0 on the z axis
    const auto branch = branch_of(system, 0, -0.64, -0.2, start);
    const auto curve = continue_equilibrium_curve(
        system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(-1, 1, -0.6, 0.3));
    ASSERT_TRUE(curve.started()) << curve.stop_reason;
    const auto zh = events_named(curve, "ZH");
    ASSERT_EQ(zh.size(), 1u) << curve.stop_reason;
    EXPECT_NEAR(zh[0].second, 0.0, 1e-8);
    const double b = coefficient(zh[0], "b"), c = coefficient(zh[0], "c");
    EXPECT_NEAR(b * c, -2.0, 2e-6) << zh[0].note;
    EXPECT_NEAR(std::abs(b), 1.0, 1e-6) << zh[0].note;
    EXPECT_NEAR(coefficient(zh[0], "a") / b, 0.8, 1e-6) << zh[0].note;
    EXPECT_EQ(coefficient(zh[0], "s"), -1.0);
    EXPECT_NEAR(coefficient(zh[0], "theta"), 0.4, 1e-6) << zh[0].note;
  }
  {
    const Warped<DoubleHopfField, 4> system;
    const auto branch = branch_of(system, 0, -0.5, 0.5, Eigen::VectorXd::Zero(4));
    const auto curve = continue_equilibrium_curve(
        system, branch, first_of(branch, EquilibriumEventType::Hopf), 1, window(-1, 1, -0.5, 0.5));
    ASSERT_TRUE(curve.started()) << curve.stop_reason;
    const auto hh = events_named(curve, "HH");
    ASSERT_EQ(hh.size(), 1u) << curve.stop_reason;
    const double expected[][2] = {{-2.0, 0}, {-1.0, 0}, {1.4, 0}, {-4.0, 0}, {0.25, 0}, {-0.7, 0}};
    const char* names[] = {"p11", "p12", "p21", "p22", "theta", "delta"};
    for (int k = 0; k < 6; ++k)
      EXPECT_NEAR(coefficient(hh[0], names[k]), expected[k][0], 1e-6 * std::abs(expected[k][0]))
          << names[k] << ": " << hh[0].note;
  }
}

// A curve from an event of the wrong kind, or in the branch's own parameter, is refused.
TEST(EquilibriumCurve, BadRequestsRefused) {
  const Cusp system;
  const auto branch = branch_of(system, 0, -1.0, 1.0, Eigen::Vector2d(-1.3247, 0.0));
  const auto& lp = first_of(branch, EquilibriumEventType::Fold);
  EXPECT_THROW(continue_equilibrium_curve(system, branch, lp, 0, window(-2, 2, -0.5, 2)),
               std::invalid_argument);
  EXPECT_THROW(continue_equilibrium_curve(system, branch, lp, 1, window(-2, 2, 1.5, 2)),
               std::invalid_argument);
  EquilibriumEvent bp = lp;
  bp.type = EquilibriumEventType::BranchPoint;
  EXPECT_THROW(continue_equilibrium_curve(system, branch, bp, 1, window(-2, 2, -0.5, 2)),
               std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
