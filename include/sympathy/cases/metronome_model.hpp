// Metronomes on a suspended platform (MODEL.md): any number of metronomes, a platform moving
// in x (1-D) or in x and y (2-D), each metronome swinging along its own direction in the
// platform plane, with its own parameters, and virtual torsion springs between chosen pairs.
//
// State: z = [x, (y), th_1..th_N, vx, (vy), vth_1..vth_N].
// Equations (general form of eq. 4 and 7-15): with e_i the swing direction, p_i = mp lp - mb lb,
// I_i = mp lp^2 + mb lb^2 and Mt = M + sum_i (mp_i + mb_i),
//   Mt r'' + C r' + K r = -sum_i p_i e_i (th_i'' cos th_i - th_i'^2 sin th_i)
//   I_i th_i'' + d_i th_i' + p_i g sin th_i = u_i - p_i (e_i . r'') cos th_i - q_i
// The mass matrix is an arrow (platform block, border b_i = p_i cos(th_i) e_i, diagonal I_i),
// so the accelerations follow from the platform block's Schur complement in O(N):
//   (Mt - sum_i b_i b_i^T / I_i) r'' = F - sum_i b_i G_i / I_i,   th_i'' = (G_i - b_i . r'') / I_i.
#pragma once

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "sympathy/core/autodiff_hybrid_system.hpp"
#include "sympathy/core/dual.hpp"

namespace sympathy {

enum class Escapement { Half, Double, Impulsive };
std::string to_string(Escapement e);
// The escapement named "half", "double" or "impulsive"; nullopt for any other name.
std::optional<Escapement> escapement_named(const std::string& name);

// The platform's named parameters over a raw layout that starts M, cx, cy, kx, ky: M, c and k
// (both directions at once on a 2-D platform), and cx, cy, kx, ky on a 2-D platform.
std::vector<NamedParameter> platform_parameters(int directions);

// The per-metronome parameters of Table I, in the order of the raw layout.
inline const std::vector<std::string>& metronome_keys() {
  static const std::vector<std::string> keys{"mp", "mb",  "lp",  "lb",  "d",
                                             "s",  "ths", "the", "eps", "angle"};
  return keys;
}

struct MetronomeSpec {
  std::map<std::string, double> values;  // every key of metronome_keys(); angle in degrees
  std::set<std::string> overridden;      // keys set for this metronome alone
};

struct SpringSpec {
  int first = 0;  // 0-based metronome indices
  int second = 1;
  double kappa = 0.0;  // N m/rad
  bool overridden = false;
};

// Everything that defines one model; case files and --set edit this, then a model is built.
struct ModelSpec {
  int directions = 1;  // platform degrees of freedom: 1 (x) or 2 (x, y)
  double M = 0.0, cx = 0.0, cy = 0.0, kx = 0.0, ky = 0.0;
  double g = 9.81;
  Escapement escapement = Escapement::Half;
  std::vector<MetronomeSpec> metronomes;
  std::vector<SpringSpec> springs;

  // Names accepted by set(): M, c, k (cx, cy, kx, ky when 2-D), g, the shared metronome keys
  // (mp, ..., eps: every metronome not overriding it), per-metronome keys with a 1-based index
  // (d2, angle3, ...), kappa (every spring not overriding it) and kappa1, kappa2, ...
  std::vector<std::string> parameter_names() const;
  bool has_parameter(const std::string& name) const;
  // Sets a parameter by name (angles in degrees); throws std::invalid_argument if unknown.
  void set(const std::string& name, double value);
  double get(const std::string& name) const;

  // Physically meaningless values, as (parameter name, what is expected); empty when valid.
  std::vector<std::pair<std::string, std::string>> problems() const;
};

// With the impulsive escapement (eq. 2) the model is piecewise smooth (HybridSystem): per
// metronome five switching surfaces, th' = 0, th = -ths, th = the, th = -the and th = ths, across
// which the torque jumps by s or not at all, and no resets. Between them it is as smooth as the
// other escapements; across them the flow carries the sensitivities by the saltation matrices,
// so orbits, monodromies and multipliers of the impulsive model are exact. Where two metronomes
// cross surfaces at one instant (in-phase and anti-phase orbits) the saltation matrices commute:
// a torque jumps only angular accelerations (through the mass matrix, every one of them), and
// every surface is a level of an angle or an angular velocity, so no crossing changes the rate at
// which another surface is reached nor the jump it makes (core/saltation.hpp checks it at each).
class MetronomeModel final : public AutoDiffHybridSystem<MetronomeModel> {
 public:
  explicit MetronomeModel(ModelSpec spec);

  const ModelSpec& spec() const { return spec_; }
  int metronome_count() const { return n_metronomes_; }
  int platform_directions() const { return directions_; }
  int angle_index(int i) const { return directions_ + i; }
  int angular_velocity_index(int i) const { return 2 * directions_ + n_metronomes_ + i; }

  int dimension() const override { return 2 * (directions_ + n_metronomes_); }
  std::vector<std::string> state_names() const override;
  // Every escapement is differentiable between switching surfaces; the impulsive one's surfaces
  // are crossed with saltation matrices (HybridSystem below).
  std::vector<SteepZone> steep_zones(const double* p) const override;
  int switching_count() const override;
  void switching_functions(double t, const double* z, const double* p, double* g) const override;
  std::string switching_name(int i) const override;  // "vth1 = 0", "th1 = -ths", "th1 = the", ...
  // HybridSystem: the field of a region named by its sides (evaluate_on_sides: the impulsive
  // torque from the sides, not from the state), the surfaces' gradients (unit vectors; ths and
  // the move the angle surfaces), no resets.
  double switching_gradient(double t, const double* z, const double* p, int surface,
                            double* h_z) const override;
  double switching_parameter_derivative(double t, const double* z, const double* p, int surface,
                                        int parameter) const override;

  // df/dz = S + U W^T (OdeSystem::low_rank_jacobian) with rank = directions: write f(z) =
  // phi(z, s) with s = r'' the platform acceleration from the Schur complement. S = dphi/dz at
  // fixed s holds q' = v and each angular acceleration's dependence on its own angle and velocity
  // and on its spring partners' angles; its platform-acceleration rows are empty. U = dphi/ds is
  // the identity in the platform-acceleration rows and -b_i^T / I_i in the angular ones;
  // W^T = d(r'')/dz, by differentiating the Schur-complement solve. O(N) per evaluation.
  std::optional<LowRankJacobian> low_rank_structure() const override;
  bool low_rank_jacobian(double t, const double* z, const double* p,
                         LowRankJacobian& out) const override;

  // Total mechanical energy (kinetic + gravity + platform spring + torsion springs), J, at
  // parameter values p.
  double mechanical_energy(const Eigen::VectorXd& z, const ParameterValues& p) const;
  // Platform mass with the metronomes' masses, Mt, at parameter values p.
  double total_mass(const ParameterValues& p) const;

  template <class T, class P>
  void evaluate(double t, const T* z, const P* raw, T* dz) const {
    evaluate_on_sides(t, z, raw, dz, nullptr);
  }
  // The same, with the impulsive torques of the region on `sides` (5 per metronome, in the order
  // of switching_functions) where not null.
  template <class T, class P>
  void evaluate_on_sides(double t, const T* z, const P* raw, T* dz, const int* sides) const;

  // On a subspace where whole metronomes move together (th_j = th_i and th_j' = th_i', nothing
  // else tied, no springs): a model of the platform and one metronome per group, each standing for
  // its group (its platform force counted once per member). Its state is the subspace's
  // coordinates, its parameters this model's. nullptr for any other subspace.
  std::unique_ptr<OdeSystem> restricted(const InvariantSubspace& subspace) const override;

 private:
  // Raw layout: [M, cx, cy, kx, ky, g], then 10 entries per metronome, then one per spring.
  static constexpr int kPlatformRaw = 6;
  static constexpr int kMetronomeRaw = 10;
  // The raw parameters of the metronome that state metronome i is (or, restricted, stands for).
  int metronome_offset(int i) const { return kPlatformRaw + kMetronomeRaw * represented_[i]; }
  int spring_offset(int j) const {
    return kPlatformRaw + kMetronomeRaw * static_cast<int>(spec_.metronomes.size()) + j;
  }

  template <class T, class P>
  T escapement(const T& th, const T& w, const P* m, const int* sides = nullptr) const;

  // Where low_rank_jacobian() writes in S's values, found once from low_rank_structure().
  struct LowRankLayout {
    std::vector<int> platform_velocity;       // row r_a, column v_a (q' = v)
    std::vector<int> angular_velocity;        // row th_i, column w_i (q' = v)
    std::vector<int> own_angle;               // row w_i, column th_i
    std::vector<int> own_velocity;            // row w_i, column w_i
    std::vector<std::pair<int, int>> spring;  // per spring: (row w_first, column th_second) and
                                              // (row w_second, column th_first)
  };
  LowRankLayout low_rank_layout() const;

  ModelSpec spec_;
  int directions_;
  int n_metronomes_;  // in the state: the spec's, or the restriction's units
  // Per state metronome: the spec's metronome it is, and how many identical metronomes moving
  // with it it stands for (1 unless restricted: their platform forces add up, each swings the
  // same).
  std::vector<int> represented_;
  std::vector<double> copies_;
  LowRankLayout layout_;
};

template <class T, class P>
T MetronomeModel::escapement(const T& th, const T& w, const P* m, const int* sides) const {
  const P& s = m[5];
  const P& ths = m[6];
  const P& the = m[7];
  const P& eps = m[8];
  using std::tanh;
  switch (spec_.escapement) {
    case Escapement::Half: {
      // Eq. 3 with the plateau s: sigma gives the sign of th', the tanh pair the window.
      const T sigma = tanh(50.0 * w / eps);
      const T st = sigma * th;
      return 0.5 * s * sigma * (tanh((st + ths) / eps) - tanh((st - the) / eps));
    }
    case Escapement::Double: {
      const T sigma = tanh(50.0 * w / eps);
      const T st = sigma * th;
      return s * sigma * (tanh((st + ths) / (2.0 * eps)) - tanh((st - the) / (2.0 * eps)));
    }
    case Escapement::Impulsive: {
      // Eq. 2: +s on -ths <= th <= the while th' > 0; -s on -the <= th <= ths while th' < 0.
      // On given sides of the surfaces (th', th + ths, th - the, th + the, th - ths): the same
      // rule, read off the sides.
      if (sides) {
        if (sides[0] > 0 && sides[1] > 0 && sides[2] < 0) return T(0.0) + s;
        if (sides[0] < 0 && sides[3] > 0 && sides[4] < 0) return T(0.0) - s;
        return T(0.0);
      }
      const double a = value_of(th), v = value_of(w);
      if (v > 0.0 && a >= -value_of(ths) && a <= value_of(the)) return T(0.0) + s;
      if (v < 0.0 && a >= -value_of(the) && a <= value_of(ths)) return T(0.0) - s;
      return T(0.0);
    }
  }
  return T(0.0);
}

template <class T, class P>
void MetronomeModel::evaluate_on_sides(double /*t*/, const T* z, const P* raw, T* dz,
                                       const int* sides) const {
  using std::cos;
  using std::sin;
  const int D = directions_;
  const int N = n_metronomes_;
  const int m = D + N;
  for (int i = 0; i < m; ++i) dz[i] = z[m + i];

  // Per-call scratch without heap traffic in the hot path: one per-thread buffer, grown only when
  // a model with more metronomes calls (resizing four vectors and zeroing one at every call was
  // 1.7% of the fast preset's instructions on the anti-phase branch).
  thread_local std::vector<T> scratch;
  if (scratch.size() < static_cast<std::size_t>(5 * N)) scratch.resize(5 * N);
  T* G = scratch.data();
  T* b = G + N;
  T* inertia = b + 2 * N;
  T* torque = inertia + N;
  const bool springs = !spec_.springs.empty();
  if (springs) std::fill(torque, torque + N, T(0.0));

  for (int j = 0; j < static_cast<int>(spec_.springs.size()); ++j) {
    const auto& spring = spec_.springs[j];
    const T q = raw[spring_offset(j)] * (z[D + spring.first] - z[D + spring.second]);
    torque[spring.first] += q;
    torque[spring.second] -= q;
  }

  const P& g = raw[5];
  P Mt = raw[0];
  // Platform force F = -C r' - K r + sum_i p_i th_i'^2 sin(th_i) e_i, and the Schur complement.
  T F[2] = {T(0.0), T(0.0)};
  for (int a = 0; a < D; ++a) F[a] = -raw[1 + a] * z[m + a] - raw[3 + a] * z[a];
  T A[3] = {T(0.0), T(0.0), T(0.0)};  // sum b b^T / I, upper triangle (00, 01, 11)
  T R[2] = {T(0.0), T(0.0)};          // sum b G / I
  for (int i = 0; i < N; ++i) {
    const P* mi = raw + metronome_offset(i);
    const P& mp = mi[0];
    const P& mb = mi[1];
    const P& lp = mi[2];
    const P& lb = mi[3];
    const double copies = copies_[i];  // identical metronomes it stands for (restricted)
    Mt = Mt + copies * (mp + mb);
    const P p = mp * lp - mb * lb;
    const P I = mp * lp * lp + mb * lb * lb;
    const P e[2] = {cos(mi[9]), sin(mi[9])};
    const T& th = z[D + i];
    const T& w = z[m + D + i];
    T sn, cs;
    sin_cos(th, sn, cs);
    const T pw2s = p * w * w * sn;
    G[i] = escapement(th, w, mi, sides ? sides + 5 * i : nullptr) - mi[4] * w - p * g * sn;
    if (springs) G[i] -= torque[i];  // subtracting a zero torque would change nothing
    inertia[i] = T(0.0) + I;
    for (int a = 0; a < D; ++a) {
      b[2 * i + a] = p * cs * e[a];
      F[a] += copies * pw2s * e[a];
      R[a] += copies * b[2 * i + a] * G[i] / I;
    }
    A[0] += copies * b[2 * i] * b[2 * i] / I;
    if (D == 2) {
      A[1] += copies * b[2 * i] * b[2 * i + 1] / I;
      A[2] += copies * b[2 * i + 1] * b[2 * i + 1] / I;
    }
  }

  // Platform accelerations from (Mt - A) r'' = F - R.
  T acc[2] = {T(0.0), T(0.0)};
  if (D == 1) {
    acc[0] = (F[0] - R[0]) / (Mt - A[0]);
  } else {
    const T s00 = Mt - A[0], s01 = -A[1], s11 = Mt - A[2];
    const T det = s00 * s11 - s01 * s01;
    const T r0 = F[0] - R[0], r1 = F[1] - R[1];
    acc[0] = (s11 * r0 - s01 * r1) / det;
    acc[1] = (s00 * r1 - s01 * r0) / det;
  }
  for (int a = 0; a < D; ++a) dz[m + a] = acc[a];
  for (int i = 0; i < N; ++i) {
    T ba = b[2 * i] * acc[0];
    if (D == 2) ba += b[2 * i + 1] * acc[1];
    dz[m + D + i] = (G[i] - ba) / inertia[i];
  }
}

}  // namespace sympathy
