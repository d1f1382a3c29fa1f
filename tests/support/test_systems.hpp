// Small systems with exactly known answers, for testing the engine.
#pragma once

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "sympathy/core/autodiff_hybrid_system.hpp"
#include "sympathy/core/autodiff_system.hpp"

namespace sympathy::testing {

// A damped oscillator coupled to a decaying mode: distinct, complex eigenvalues (for LinearSystem).
inline Eigen::MatrixXd oscillator_matrix() {
  Eigen::MatrixXd a(3, 3);
  a << 0.0, 1.0, 0.0, -4.0, -0.3, 0.5, 0.2, 0.0, -1.5;
  return a;
}

// z' = A z with a constant matrix; solution expm(A t) z0.
class LinearSystem final : public AutoDiffSystem<LinearSystem> {
 public:
  explicit LinearSystem(Eigen::MatrixXd a) : a_(std::move(a)) {
    set_parameter_layout({{"scale", {0}}}, {1.0});
  }
  int dimension() const override { return static_cast<int>(a_.rows()); }
  std::vector<std::string> state_names() const override {
    std::vector<std::string> n;
    for (int i = 0; i < dimension(); ++i)
      n.push_back(std::string("z").append(std::to_string(i + 1)));
    return n;
  }
  // z' = scale * A z
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    for (int i = 0; i < dimension(); ++i) {
      T sum(0.0);
      for (int j = 0; j < dimension(); ++j) sum += a_(i, j) * z[j];
      dz[i] = p[0] * sum;
    }
  }

 private:
  Eigen::MatrixXd a_;
};

// z' = -a z: z(t) = z0 exp(-a t), dz/da = -t z0 exp(-a t).
class Decay final : public AutoDiffSystem<Decay> {
 public:
  explicit Decay(double a) { set_parameter_layout({{"a", {0}}}, {a}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"z"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = -p[0] * z[0];
  }
};

// A damped oscillator m x'' + c x' + k x = 0, states x and v = x'. Only c/m and k/m enter its
// motion, so m, c and k together are not determined by a trajectory.
class DampedOscillator final : public AutoDiffSystem<DampedOscillator> {
 public:
  DampedOscillator(double m, double c, double k) {
    set_parameter_layout({{"m", {0}}, {"c", {1}}, {"k", {2}}}, {m, c, k});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = z[1];
    dz[1] = (-p[1] * z[1] - p[2] * z[0]) / p[0];
  }
};

// z' = z^2: blows up at t = 1/z0.
class BlowUp final : public AutoDiffSystem<BlowUp> {
 public:
  BlowUp() { set_parameter_layout({}, {}); }
  int dimension() const override { return 1; }
  std::vector<std::string> state_names() const override { return {"z"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    dz[0] = z[0] * z[0];
  }
};

// u' = -1 and q' = exp(-(u/w)^2) / (w sqrt(pi)): a pulse of unit area, width w, as u crosses 0.
// From u = 1 to u = -1, q gains erf(1/w) = 1 to machine precision. Error control alone steps
// over the pulse; the flow must resolve it through the steep zone on u.
// With `copies` > 1, that many identical (u, q) pairs side by side: from equal starts their
// zones are crossed at the same instants.
class Pulse final : public AutoDiffSystem<Pulse> {
 public:
  explicit Pulse(double width, int copies = 1) : width_(width), copies_(copies) {
    set_parameter_layout({}, {});
  }
  int dimension() const override { return 2 * copies_; }
  std::vector<std::string> state_names() const override {
    std::vector<std::string> names;
    for (int c = 0; c < copies_; ++c) {
      const std::string suffix = copies_ > 1 ? std::to_string(c + 1) : "";
      names.push_back("u" + suffix);
      names.push_back("q" + suffix);
    }
    return names;
  }
  std::vector<SteepZone> steep_zones(const double* /*p*/) const override {
    std::vector<SteepZone> zones;
    for (int c = 0; c < copies_; ++c) zones.push_back({2 * c, width_, 1.0});
    return zones;
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    using std::exp;
    for (int c = 0; c < copies_; ++c) {
      const T s = z[2 * c] / width_;
      dz[2 * c] = T(-1.0);
      dz[2 * c + 1] = exp(-s * s) / (width_ * std::sqrt(M_PI));
    }
  }

 private:
  double width_;
  int copies_;
};

// The Hopf normal form x' = -y + x(1 - r^2), y' = x + y(1 - r^2): the unit circle is a limit
// cycle of period 2 pi with radial multiplier exp(-4 pi). With `transverse`, a third state
// w' = (-a + b x) w whose multiplier on the cycle (x = cos t) is exp(-2 pi a) exactly.
class HopfCycle final : public AutoDiffSystem<HopfCycle> {
 public:
  explicit HopfCycle(bool transverse = false, double a = 0.5, double b = 0.7)
      : transverse_(transverse) {
    set_parameter_layout({{"a", {0}}, {"b", {1}}}, {a, b});
  }
  int dimension() const override { return transverse_ ? 3 : 2; }
  std::vector<std::string> state_names() const override {
    if (transverse_) return {"x", "y", "w"};
    return {"x", "y"};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T g = 1.0 - (z[0] * z[0] + z[1] * z[1]);
    dz[0] = -z[1] + z[0] * g;
    dz[1] = z[0] + z[1] * g;
    if (transverse_) dz[2] = (-p[0] + p[1] * z[0]) * z[2];
  }

 private:
  bool transverse_;
};

// Two Hopf oscillators (a_i, b_i) of frequency w on a damped "platform" x: a_i' = -w b_i + a_i g_i
// - kappa (a_1 + a_2) + eps x, b_i' = w a_i + b_i g_i - kappa (b_1 + b_2), g_i = 1 - a_i^2 - b_i^2,
// x' = -gamma x + mu (a_1 + a_2). It keeps the reflection (a1, b1, a2, b2, x) -> (-a2, -b2, -a1,
// -b1, -x), whose fixed space x = 0, a2 = -a1, b2 = -b1 holds the anti-phase orbit a1 = cos(w t),
// b1 = sin(w t) of period 2 pi / w, on which kappa, eps, gamma and mu do not act (w does).
// Inside the fixed space its multipliers are the Hopf cycle's, 1 and exp(-4 pi / w). Across it
// (the sums s = (a1 + a2, b1 + b2) / sqrt(2) and x), with eps = 0: s' = (J_Hopf(t) - 2 kappa) s
// gives exp(-4 pi kappa / w) and exp(-4 pi (1 + kappa) / w), and x, driven by s but not driving
// it, exp(-2 pi gamma / w).
class SymmetricPair final : public AutoDiffSystem<SymmetricPair> {
 public:
  explicit SymmetricPair(double eps = 0.0) {
    set_parameter_layout({{"w", {0}}, {"kappa", {1}}, {"eps", {2}}, {"gamma", {3}}, {"mu", {4}}},
                         {1.0, 0.1, eps, 0.5, 0.3});
  }
  int dimension() const override { return 5; }
  std::vector<std::string> state_names() const override { return {"a1", "b1", "a2", "b2", "x"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T sa = z[0] + z[2], sb = z[1] + z[3];
    for (int k = 0; k < 4; k += 2) {
      const T g = 1.0 - (z[k] * z[k] + z[k + 1] * z[k + 1]);
      dz[k] = -p[0] * z[k + 1] + z[k] * g - p[1] * sa + p[2] * z[4];
      dz[k + 1] = p[0] * z[k] + z[k + 1] * g - p[1] * sb;
    }
    dz[4] = -p[3] * z[4] + p[4] * sa;
  }
};

// Two uncoupled Hopf oscillators of the same frequency: every phase difference gives a periodic
// orbit (a one-parameter family), with multipliers 1, 1, exp(-4 pi), exp(-4 pi).
class TwoHopf final : public AutoDiffSystem<TwoHopf> {
 public:
  TwoHopf() { set_parameter_layout({}, {}); }
  int dimension() const override { return 4; }
  std::vector<std::string> state_names() const override { return {"x1", "y1", "x2", "y2"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P*, T* dz) const {
    for (int k = 0; k < 4; k += 2) {
      const T g = 1.0 - (z[k] * z[k] + z[k + 1] * z[k + 1]);
      dz[k] = -z[k + 1] + z[k] * g;
      dz[k + 1] = z[k] + z[k + 1] * g;
    }
  }
};

// Normal forms of bifurcations of periodic orbits around the unit circle (theta' = 1, period
// 2 pi), each with one parameter mu and the bifurcation at an exactly known value; a second
// parameter a (0 by default) moves it along an exactly known curve: the transverse growth rate
// is mu - a^2 in the pitchfork, rotation and Moebius forms (BP, NS, PD curves mu = a^2), and the
// fold form's cycles r^2 solve mu + (1 + a) r^2 - r^4 = 0 (LP curve mu = -(1 + a)^2 / 4 at
// r^2 = (1 + a) / 2). The rotation form's angle per period is 2 pi omega (omega 0.3 by default;
// the rotation number of its NS pair).
//   Fold:       r' = r (mu + r^2 - r^4): cycles at mu = r^4 - r^2, a fold at mu = -1/4
//               (r^2 = 1/2), where the radial multiplier exp(2 pi (2 r^2 - 4 r^4)) is 1.
//   ShearedFold: the same with theta' = 1 + omega r^2: the period 2 pi / (1 + omega r^2)
//               changes along the family, so at the fold the multiplier 1 is a 2x2 Jordan
//               block (M v = v + alpha f), the generic fold of cycles.
//   Pitchfork:  r' = r (1 - r^2), w_k' = mu w_k - w_k^3 for `copies` transverse states: on
//               w = 0 the multipliers exp(2 pi mu) cross +1 at mu = 0 (together if copies = 2).
//   Rotation:   r' = r (1 - r^2), (u, v) rotating at 0.3 and growing at mu, cubically
//               saturated: multipliers exp(2 pi (mu +- 0.3 i)), a Neimark-Sacker pair at mu = 0.
//   PitchforkAndGrowth: the pitchfork's w1 beside s' = (a - 1/2) s - s^3, whose multiplier
//               exp(2 pi (a - 1/2)) crosses +1 at a = 1/2: on the BP curve mu = a^2, at
//               (mu, a) = (1/4, 1/2), another multiplier crosses the unit circle.
//   RotationAndGrowth: Rotation beside s' = (a - 1/2) s - s^3 (mu - a^2 for mu, as every
//               kind but Fold): the NS curve mu = a^2, along which the s-multiplier
//               exp(2 pi (a - 1/2)) crosses +1 at (mu, a) = (1/4, 1/2). With no subspace declared
//               the NS pair, the trivial multiplier and that one share a block.
//   Resonance:  as Rotation with the transverse block [mu, 1; -omega, mu]: the pair
//               exp(2 pi (mu +- sqrt(-omega))), complex for omega > 0 (NS on mu = 0, rotation
//               number sqrt(omega)), meeting at +1 at (mu, omega) = (0, 0) (1:1 resonance) and
//               real beyond, one of them at +1 on omega = -mu^2 (a BP curve through it).
//   Moebius:    r' from a transverse plane (a = r - 1, z) that turns half a revolution per
//               period: in the frame turning with theta / 2, xi' = mu xi - xi^3 and eta' = -eta,
//               so the multipliers are -exp(2 pi mu) and -exp(-2 pi): period doubling at
//               mu = 0, the doubled orbit xi = +-sqrt(mu) of period 4 pi beyond it.
//   RotatingMoebius: Moebius written in (theta, a, w) with theta' = 1 an angle state
//               (angle_states): the orbit a = w = 0 gains 2 pi in theta each period, so its
//               shooting residual is Phi_T(z0) - 2 pi e_theta - z0; the same multipliers, PD at
//               mu = 0 and, with mu - a^2 for mu, the PD curve mu = a^2.
//   MoebiusPair: the same turning plane with the linear w' = (mu I + omega J + c K) w in the
//               turning frame (J the rotation generator, K = diag(1, -1), c = 1/2): multipliers
//               -exp(2 pi (mu +- sqrt(c^2 - omega^2))) exactly, a complex pair for omega > c
//               that meets on the negative axis at omega = c, after which one of them passes -1
//               where mu + sqrt(c^2 - omega^2) = 0 (for mu < 0: omega = sqrt(c^2 - mu^2)).
class NormalForm final : public AutoDiffSystem<NormalForm> {
 public:
  enum class Kind {
    Fold,
    Pitchfork,
    Rotation,
    Moebius,
    PitchforkAndGrowth,
    ShearedFold,
    Resonance,
    RotationAndGrowth,
    MoebiusPair,
    RotatingMoebius
  };
  NormalForm(Kind kind, double mu, int copies = 1, double a = 0.0, double omega = 0.3)
      : kind_(kind), copies_(copies) {
    set_parameter_layout({{"mu", {0}}, {"a", {1}}, {"omega", {2}}}, {mu, a, omega});
  }
  int dimension() const override {
    switch (kind_) {
      case Kind::Fold:
      case Kind::ShearedFold:
        return 2;
      case Kind::Pitchfork:
        return 2 + copies_;
      case Kind::Rotation:
      case Kind::Resonance:
        return 4;
      case Kind::Moebius:
      case Kind::MoebiusPair:
      case Kind::RotatingMoebius:
        return 3;
      case Kind::PitchforkAndGrowth:
        return 4;
      case Kind::RotationAndGrowth:
        return 5;
    }
    return 2;
  }
  std::vector<int> angle_states() const override {
    return kind_ == Kind::RotatingMoebius ? std::vector<int>{0} : std::vector<int>{};
  }
  std::vector<std::string> state_names() const override {
    if (kind_ == Kind::RotatingMoebius) return {"theta", "a", "w"};
    std::vector<std::string> n{"x", "y"};
    for (int i = 2; i < dimension(); ++i)
      n.push_back(std::string("w").append(std::to_string(i - 1)));
    return n;
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    using std::sqrt;
    const bool fold = kind_ == Kind::Fold || kind_ == Kind::ShearedFold;
    const P mu = fold ? P(p[0]) : P(p[0] - p[1] * p[1]);
    const P& omega = p[2];
    const T r2 = z[0] * z[0] + z[1] * z[1];
    if (kind_ == Kind::MoebiusPair) {
      // [a; w]' = (J/2 + mu I + omega J + c S(theta)) [a; w], S(theta) = R(theta/2) K R(-theta/2)
      // = [cos, sin; sin, -cos](theta): the turning frame's A conjugated into the fixed one.
      const T r = sqrt(r2);
      const T c = z[0] / r, s = z[1] / r, a = r - 1.0, w = z[2];
      const double k = 0.5;
      const T da = -0.5 * w + mu * a - omega * w + k * (c * a + s * w);
      const T dw = 0.5 * a + mu * w + omega * a + k * (s * a - c * w);
      dz[0] = -z[1] + c * da;
      dz[1] = z[0] + s * da;
      dz[2] = dw;
      return;
    }
    if (kind_ == Kind::Moebius || kind_ == Kind::RotatingMoebius) {
      using std::cos;
      using std::sin;
      const bool polar = kind_ == Kind::RotatingMoebius;
      const T r = sqrt(r2);
      const T c = polar ? T(cos(z[0])) : T(z[0] / r), s = polar ? T(sin(z[0])) : T(z[1] / r);
      const T a = polar ? z[1] : T(r - 1.0), w = z[2];
      const T cc = 0.5 * (1.0 + c), ss = 0.5 * (1.0 - c), cs = 0.5 * s;  // of theta / 2
      const T xi2 = a * a * cc + 2.0 * a * w * cs + w * w * ss;
      // [a; w]' = (J/2 + (mu - 1)/2 I + (mu + 1)/2 S(theta)) [a; w] - xi^2 xi [cos; sin](theta/2)
      const T da = -0.5 * w + 0.5 * (mu - 1.0) * a + 0.5 * (mu + 1.0) * (c * a + s * w) -
                   xi2 * (a * cc + w * cs);
      const T dw = 0.5 * a + 0.5 * (mu - 1.0) * w + 0.5 * (mu + 1.0) * (s * a - c * w) -
                   xi2 * (a * cs + w * ss);
      if (polar) {
        dz[0] = T(1.0);
        dz[1] = da;
      } else {
        dz[0] = -z[1] + c * da;
        dz[1] = z[0] + s * da;
      }
      dz[2] = dw;
      return;
    }
    const T g = fold ? T(mu + (1.0 + p[1]) * r2 - r2 * r2) : T(1.0 - r2);
    if (kind_ == Kind::ShearedFold) {
      const T w = 1.0 + omega * r2;  // the angular speed grows with the radius
      dz[0] = -w * z[1] + z[0] * g;
      dz[1] = w * z[0] + z[1] * g;
      return;
    }
    dz[0] = -z[1] + z[0] * g;
    dz[1] = z[0] + z[1] * g;
    if (kind_ == Kind::Pitchfork)
      for (int k = 2; k < dimension(); ++k) dz[k] = mu * z[k] - z[k] * z[k] * z[k];
    if (kind_ == Kind::PitchforkAndGrowth) {
      dz[2] = mu * z[2] - z[2] * z[2] * z[2];
      dz[3] = (p[1] - 0.5) * z[3] - z[3] * z[3] * z[3];
    }
    if (kind_ == Kind::RotationAndGrowth) dz[4] = (p[1] - 0.5) * z[4] - z[4] * z[4] * z[4];
    if (kind_ == Kind::Rotation || kind_ == Kind::RotationAndGrowth) {
      const T q = z[2] * z[2] + z[3] * z[3];
      dz[2] = mu * z[2] - omega * z[3] - z[2] * q;
      dz[3] = omega * z[2] + mu * z[3] - z[3] * q;
    }
    if (kind_ == Kind::Resonance) {
      const T q = z[2] * z[2] + z[3] * z[3];
      dz[2] = mu * z[2] + z[3] - z[2] * q;
      dz[3] = -omega * z[2] + mu * z[3] - z[3] * q;
    }
  }

 private:
  Kind kind_;
  int copies_;
};

// z' = A(t) z with A(t) = [0 1; -10 cos t, -24 - 10 sin t], period 2 pi. In second-order form
// x'' + (24 + 10 sin t) x' + 10 cos t x = d/dt (x' + (24 + 10 sin t) x) = 0, so the Floquet
// exponents are exactly 0 and -24 (multipliers 1 and exp(-48 pi) = 2e-66).
class ForcedFloquet final : public AutoDiffSystem<ForcedFloquet> {
 public:
  ForcedFloquet() { set_parameter_layout({}, {}); }
  int dimension() const override { return 2; }
  bool autonomous() const override { return false; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double t, const T* z, const P*, T* dz) const {
    dz[0] = z[1];
    dz[1] = -10.0 * std::cos(t) * z[0] - (24.0 + 10.0 * std::sin(t)) * z[1];
  }
};

// The Hopf cycle scaled to radius R: x' = -y + x (1 - r^2 / R^2), y' = x + y (1 - r^2 / R^2),
// its limit cycle the circle r = R, period 2 pi, radial multiplier exp(-4 pi) for every R; with
// the parameter mu the growth is 1 + mu - r^2 / R^2 and the cycle r = R sqrt(1 + mu): a branch
// in mu whose states are of order R.
class ScaledCircle final : public AutoDiffSystem<ScaledCircle> {
 public:
  explicit ScaledCircle(double radius) : radius_(radius) {
    set_parameter_layout({{"mu", {0}}}, {0.0});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T g = 1.0 + p[0] - (z[0] * z[0] + z[1] * z[1]) / (radius_ * radius_);
    dz[0] = -z[1] + z[0] * g;
    dz[1] = z[0] + z[1] * g;
  }

 private:
  double radius_;
};

// AUTO-07p's demo lcbp: x' = -x G - 2 pi y, y' = -y G + 2 pi x, G = (r - p1)(r - p2) with
// r = sqrt(x^2 + y^2). The circles r = p1 and r = p2 are orbits of period 1 whatever the
// parameters; the circle r = p2 has the radial multiplier exp(-p2 (p2 - p1)) (r' = -r G
// linearized there), which crosses +1 at p1 = p2, where the two families cross transversally:
// a transcritical branch point of cycles, exactly at p1 = p2.
class CrossingCircles final : public AutoDiffSystem<CrossingCircles> {
 public:
  CrossingCircles(double p1, double p2) {
    set_parameter_layout({{"p1", {0}}, {"p2", {1}}}, {p1, p2});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    using std::sqrt;
    const T r = sqrt(z[0] * z[0] + z[1] * z[1]);
    const T g = (r - p[0]) * (r - p[1]);
    dz[0] = -z[0] * g - 2.0 * std::numbers::pi * z[1];
    dz[1] = -z[1] * g + 2.0 * std::numbers::pi * z[0];
  }
};

// Branches of equilibria with exactly known events, a second state y' = -y beside them:
//   SaddleNode:    x' = p - x^2: x = +-sqrt(p), a fold at p = 0 (x = 0);
//   Transcritical: x' = p x - x^2: the branches x = 0 and x = p cross at p = 0, a branch point;
//   DoublePitchfork: x' = p x - x^3 and y' = p y - y^3 instead: at the origin both eigenvalues
//                  are p, two pitchforks at p = 0 at once (the bordered determinant goes as p^2
//                  and keeps its sign: only the count of unstable eigenvalues, 0 to 2, sees it).
class Equilibria1D final : public AutoDiffSystem<Equilibria1D> {
 public:
  enum class Kind { SaddleNode, Transcritical, DoublePitchfork };
  explicit Equilibria1D(Kind kind, double p = 1.0) : kind_(kind) {
    set_parameter_layout({{"p", {0}}}, {p});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    if (kind_ == Kind::DoublePitchfork) {
      dz[0] = p[0] * z[0] - z[0] * z[0] * z[0];
      dz[1] = p[0] * z[1] - z[1] * z[1] * z[1];
      return;
    }
    dz[0] = kind_ == Kind::SaddleNode ? T(p[0] - z[0] * z[0]) : T(p[0] * z[0] - z[0] * z[0]);
    dz[1] = -z[1];
  }

 private:
  Kind kind_;
};

// A branch point of equilibria with no eigenvector on a coordinate axis: in w = R^T z (R a
// rotation by 0.6 rad) the normal form u' = p u - u^2 (Transcritical) or p u - u^3 (Pitchfork),
// v' = -v, turned back by R and multiplied by M(z) = [1 + 0.2 z1, 0.1 z0; -0.15 z1, 1 + 0.2 z0]
// (invertible for |z| < 1.5: det > 0.4), which moves every Jacobian but no equilibrium. So the
// equilibria are exactly R (u, 0) with u = 0 or u = p (u^2 = p), and the branch point is at
// p = 0, z = 0, as in the normal form.
class TurnedBranchPoint final : public AutoDiffSystem<TurnedBranchPoint> {
 public:
  enum class Kind { Transcritical, Pitchfork };
  explicit TurnedBranchPoint(Kind kind, double p = -1.0) : kind_(kind) {
    set_parameter_layout({{"p", {0}}}, {p});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"z0", "z1"}; }
  // z = R (u, v).
  static Eigen::Vector2d turned(double u, double v) {
    return {kCos * u - kSin * v, kSin * u + kCos * v};
  }
  // (u, v) = R^T z.
  static Eigen::Vector2d normal(const Eigen::VectorXd& z) {
    return {kCos * z[0] + kSin * z[1], -kSin * z[0] + kCos * z[1]};
  }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T u = kCos * z[0] + kSin * z[1];
    const T v = -kSin * z[0] + kCos * z[1];
    const T gu = kind_ == Kind::Transcritical ? T(p[0] * u - u * u) : T(p[0] * u - u * u * u);
    const T gv = -v;
    const T h0 = kCos * gu - kSin * gv;
    const T h1 = kSin * gu + kCos * gv;
    dz[0] = (1.0 + 0.2 * z[1]) * h0 + 0.1 * z[0] * h1;
    dz[1] = -0.15 * z[1] * h0 + (1.0 + 0.2 * z[0]) * h1;
  }

 private:
  static constexpr double kCos = 0.82533561490967829724;  // cos 0.6
  static constexpr double kSin = 0.56464247339503535720;  // sin 0.6
  Kind kind_;
};

// x' = y, y' = b1 + b2 x + x^2 - x y: equilibria (x, 0) with x^2 + b2 x + b1 = 0, Jacobian
// [0 1; b2 + 2x, -x]: folds on b1 = b2^2 / 4 (x = -b2 / 2), trace zero at x = 0 (b1 = 0) with
// det = -b2: Hopf for b2 < 0 (omega^2 = -b2), a neutral saddle for b2 > 0, Bogdanov-Takens at the
// origin. Defaults b1 = 0.1, b2 = -1.
class BogdanovTakens final : public AutoDiffSystem<BogdanovTakens> {
 public:
  BogdanovTakens() { set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {0.1, -1.0}); }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = z[1];
    dz[1] = p[0] + p[1] * z[0] + z[0] * z[0] - z[0] * z[1];
  }
};

// Piecewise-smooth systems with closed-form periodic orbits (HybridSystem: modes, surfaces,
// resets), for the flow's crossings and saltation matrices.
//
// Relay: `copies` relay oscillators x_i'' + 2 zeta x_i' + x_i = a s_i + c a sum_(j != i) s_j,
// s_i = sign(x_i'), states (x_i, v_i), surfaces h_i = v_i (the turning points), parameters zeta,
// a and c (the cross-coupling, 0 by default). Between turning points each copy is a damped
// oscillator about x = +-a (c = 0), so a half swing takes pi / w, w = sqrt(1 - zeta^2), and shrinks
// the distance to the centre by rho = exp(-zeta pi / w): from the bottom turning point -A the
// swing ends at a + rho (A + a). The symmetric orbit between -A and A, A = a + rho (A + a), that
// is A = a (1 + rho) / (1 - rho), has period T = 2 pi / w exactly. Its multipliers are 1 and
// rho^2: the half-swing map of the amplitude, A -> a + rho (A + a), has slope rho; and for one copy
// det(monodromy) = det(e^(M T)) det(S_top) det(S_bottom) = rho^4 ((A + a) / (A - a))^2 = rho^2
// agrees (at the top S = I + (f+ - f-) e_v^T / v'-, whose v-v entry is (A + a) / (A - a)). A
// quarter swing after the bottom turning point the orbit passes x = a - (A + a) e^(-zeta pi / (2
// w)) zeta / w, v = (A + a) e^(-zeta pi / (2 w)) / w. With copies > 1 and c = 0 the copies are
// uncoupled: from equal starts they cross their surfaces at the same instants, with saltation
// matrices that act on their own copy's velocity only, and commute; the multipliers are 1, 1 (the
// copies' relative phase is free), rho^2, rho^2. With c != 0 a turning point of one copy jumps the
// others' acceleration too: simultaneous crossings then do not commute (a corner).
class Relay final : public AutoDiffHybridSystem<Relay> {
 public:
  explicit Relay(double zeta = 0.1, double a = 0.5, int copies = 1, double c = 0.0)
      : copies_(copies) {
    set_parameter_layout({{"zeta", {0}}, {"a", {1}}, {"c", {2}}}, {zeta, a, c});
  }
  int dimension() const override { return 2 * copies_; }
  std::vector<std::string> state_names() const override {
    std::vector<std::string> names;
    for (int i = 1; i <= copies_; ++i) {
      names.push_back(std::string("x").append(std::to_string(i)));
      names.push_back(std::string("v").append(std::to_string(i)));
    }
    return names;
  }
  // The region is read off the velocities (v = 0 counts as v > 0).
  template <class T, class P>
  void evaluate(double t, const T* z, const P* p, T* dz) const {
    std::vector<int> sides(copies_);
    for (int i = 0; i < copies_; ++i) sides[i] = value_of(z[2 * i + 1]) >= 0.0 ? 1 : -1;
    evaluate_on_sides(t, z, p, dz, sides.data());
  }
  template <class T, class P>
  void evaluate_on_sides(double, const T* z, const P* p, T* dz, const int* sides) const {
    int sum = 0;
    for (int i = 0; i < copies_; ++i) sum += sides[i];
    for (int i = 0; i < copies_; ++i) {
      dz[2 * i] = z[2 * i + 1];
      dz[2 * i + 1] = -z[2 * i] - 2.0 * p[0] * z[2 * i + 1] + p[1] * sides[i] +
                      p[2] * p[1] * static_cast<double>(sum - sides[i]);
    }
  }
  int switching_count() const override { return copies_; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    for (int i = 0; i < copies_; ++i) g[i] = z[2 * i + 1];
  }
  double switching_gradient(double, const double*, const double*, int surface,
                            double* h_z) const override {
    for (int i = 0; i < dimension(); ++i) h_z[i] = i == 2 * surface + 1 ? 1.0 : 0.0;
    return 0.0;
  }

  // The closed form above, at zeta and a.
  static double angular_frequency(double zeta) { return std::sqrt(1.0 - zeta * zeta); }
  static double contraction(double zeta) {  // rho
    return std::exp(-zeta * std::numbers::pi / angular_frequency(zeta));
  }
  static double amplitude(double zeta, double a) {
    const double rho = contraction(zeta);
    return a * (1.0 + rho) / (1.0 - rho);
  }
  // (x, v) a quarter swing after the bottom turning point.
  static Eigen::Vector2d quarter_point(double zeta, double a) {
    const double w = angular_frequency(zeta);
    const double decay = (amplitude(zeta, a) + a) * std::exp(-zeta * std::numbers::pi / (2 * w));
    return {a - decay * zeta / w, decay / w};
  }

 private:
  int copies_;
};

// An impact oscillator: x'' + 2 zeta x' + x = 0 above a wall at x = 0 (surface h = x, crossed
// downwards only), where the velocity is reset to v+ = w - e v- (restitution e and a kick w:
// an impact that gives energy back). From the wall at v = V the motion x = V e^(-zeta t)
// sin(w t) / w, w = sqrt(1 - zeta^2), returns to it at t = pi / w with v = -rho V, rho =
// exp(-zeta pi / w); the period-one orbit has V = w_kick / (1 - e rho) and period T = pi / w
// exactly; its multipliers are 1 and e rho (the impact map V -> w_kick + e rho V). Parameters
// zeta, e, kick.
class ImpactOscillator final : public AutoDiffHybridSystem<ImpactOscillator> {
 public:
  ImpactOscillator(double zeta = 0.1, double e = 0.8, double kick = 1.0) {
    set_parameter_layout({{"zeta", {0}}, {"e", {1}}, {"kick", {2}}}, {zeta, e, kick});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "v"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    dz[0] = z[1];
    dz[1] = -z[0] - 2.0 * p[0] * z[1];
  }
  // The same field on both sides (the wall only resets).
  template <class T, class P>
  void evaluate_on_sides(double t, const T* z, const P* p, T* dz, const int*) const {
    evaluate(t, z, p, dz);
  }
  int switching_count() const override { return 1; }
  void switching_functions(double, const double* z, const double*, double* g) const override {
    g[0] = z[0];
  }
  int crossing_direction(int) const override { return -1; }
  double switching_gradient(double, const double*, const double*, int, double* h_z) const override {
    h_z[0] = 1.0;
    h_z[1] = 0.0;
    return 0.0;
  }
  bool has_reset(int) const override { return true; }
  void reset(double, const double* z, const double* p, int, double* z_plus) const override {
    z_plus[0] = z[0];
    z_plus[1] = p[2] - p[1] * z[1];
  }
  void reset_jacobian(double, const double*, const double* p, int,
                      Eigen::MatrixXd& r_z) const override {
    r_z = Eigen::Matrix2d{{1.0, 0.0}, {0.0, -p[1]}};
  }
  void reset_parameter_derivative(double, const double* z, const double*, int, int parameter,
                                  double* r_p) const override {
    r_p[0] = 0.0;
    r_p[1] = parameter == 1 ? -z[1] : parameter == 2 ? 1.0 : 0.0;
  }

  // The closed form above.
  static double period(double zeta) { return std::numbers::pi / std::sqrt(1.0 - zeta * zeta); }
  static double contraction(double zeta) { return std::exp(-zeta * period(zeta)); }
  static double impact_velocity(double zeta, double e, double kick) {  // V, just after the wall
    return kick / (1.0 - e * contraction(zeta));
  }
};

}  // namespace sympathy::testing
