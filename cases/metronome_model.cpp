#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/names.hpp"
#include "sympathy/core/invariant_subspace.hpp"

#include <algorithm>
#include <array>
#include <numbers>
#include <numeric>
#include <stdexcept>

namespace sympathy {

std::string to_string(Escapement e) {
  switch (e) {
    case Escapement::Half:
      return "half";
    case Escapement::Double:
      return "double";
    case Escapement::Impulsive:
      return "impulsive";
  }
  return "?";
}

std::optional<Escapement> escapement_named(const std::string& name) {
  for (Escapement e : {Escapement::Half, Escapement::Double, Escapement::Impulsive})
    if (to_string(e) == name) return e;
  return std::nullopt;
}

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

bool is_metronome_key(const std::string& key) {
  const auto& keys = metronome_keys();
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace

std::vector<NamedParameter> platform_parameters(int directions) {
  std::vector<NamedParameter> named{{"M", {0}}};
  if (directions == 1) {
    named.push_back({"c", {1}});
    named.push_back({"k", {3}});
  } else {
    named.push_back({"c", {1, 2}});
    named.push_back({"k", {3, 4}});
    named.push_back({"cx", {1}});
    named.push_back({"cy", {2}});
    named.push_back({"kx", {3}});
    named.push_back({"ky", {4}});
  }
  return named;
}

std::vector<std::string> ModelSpec::parameter_names() const {
  std::vector<std::string> names{"M", "c", "k"};
  if (directions == 2) names.insert(names.end(), {"cx", "cy", "kx", "ky"});
  names.push_back("g");
  for (const auto& key : metronome_keys()) {
    if (key == "angle") continue;
    for (const auto& m : metronomes)
      if (!m.overridden.count(key)) {
        names.push_back(key);
        break;
      }
  }
  for (std::size_t i = 0; i < metronomes.size(); ++i)
    for (const auto& key : metronome_keys()) names.push_back(key + std::to_string(i + 1));
  if (std::any_of(springs.begin(), springs.end(), [](auto& s) { return !s.overridden; }))
    names.push_back("kappa");
  for (std::size_t j = 0; j < springs.size(); ++j) names.push_back("kappa" + std::to_string(j + 1));
  return names;
}

bool ModelSpec::has_parameter(const std::string& name) const {
  const auto names = parameter_names();
  return std::find(names.begin(), names.end(), name) != names.end();
}

void ModelSpec::set(const std::string& name, double value) {
  if (name == "M") {
    M = value;
  } else if (name == "c") {
    cx = cy = value;
  } else if (name == "k") {
    kx = ky = value;
  } else if (directions == 2 && name == "cx") {
    cx = value;
  } else if (directions == 2 && name == "cy") {
    cy = value;
  } else if (directions == 2 && name == "kx") {
    kx = value;
  } else if (directions == 2 && name == "ky") {
    ky = value;
  } else if (name == "g") {
    g = value;
  } else if (name == "kappa") {
    for (auto& s : springs)
      if (!s.overridden) s.kappa = value;
  } else if (is_metronome_key(name) && name != "angle") {
    for (auto& m : metronomes)
      if (!m.overridden.count(name)) m.values[name] = value;
  } else {
    auto [key, index] = split_index(name);
    if (key == "kappa" && index >= 1 && index <= static_cast<int>(springs.size())) {
      springs[index - 1].kappa = value;
      springs[index - 1].overridden = true;
    } else if (is_metronome_key(key) && index >= 1 &&
               index <= static_cast<int>(metronomes.size())) {
      metronomes[index - 1].values[key] = value;
      metronomes[index - 1].overridden.insert(key);
    } else {
      std::string known;
      for (const auto& n : parameter_names()) known += (known.empty() ? "" : ", ") + n;
      throw std::invalid_argument("unknown parameter '" + name + "'; expected one of: " + known);
    }
  }
}

double ModelSpec::get(const std::string& name) const {
  if (name == "M") return M;
  if (name == "c" || name == "cx") return cx;
  if (name == "cy" && directions == 2) return cy;
  if (name == "k" || name == "kx") return kx;
  if (name == "ky" && directions == 2) return ky;
  if (name == "g") return g;
  if (name == "kappa")
    for (const auto& s : springs)
      if (!s.overridden) return s.kappa;
  if (is_metronome_key(name))
    for (const auto& m : metronomes)
      if (!m.overridden.count(name)) return m.values.at(name);
  auto [key, index] = split_index(name);
  if (key == "kappa" && index >= 1 && index <= static_cast<int>(springs.size()))
    return springs[index - 1].kappa;
  if (is_metronome_key(key) && index >= 1 && index <= static_cast<int>(metronomes.size()))
    return metronomes[index - 1].values.at(key);
  throw std::invalid_argument("unknown parameter '" + name + "'");
}

std::vector<std::pair<std::string, std::string>> ModelSpec::problems() const {
  std::vector<std::pair<std::string, std::string>> out;
  auto check = [&](const std::string& name, double v, bool positive) {
    if (!std::isfinite(v))
      out.emplace_back(name, "a finite number");
    else if (positive && !(v > 0.0))
      out.emplace_back(name, "a positive number");
    else if (!positive && v < 0.0)
      out.emplace_back(name, "a non-negative number");
  };
  if (directions != 1 && directions != 2) out.emplace_back("directions", "1 or 2");
  check("M", M, true);
  check(directions == 2 ? "cx" : "c", cx, false);
  check(directions == 2 ? "kx" : "k", kx, false);
  if (directions == 2) {
    check("cy", cy, false);
    check("ky", ky, false);
  }
  check("g", g, true);
  if (metronomes.empty()) out.emplace_back("metronomes", "at least one metronome");
  for (std::size_t i = 0; i < metronomes.size(); ++i) {
    const auto& v = metronomes[i].values;
    const std::string id = std::to_string(i + 1);
    for (const auto& key : metronome_keys()) {
      if (!v.count(key)) {
        out.emplace_back(key + id, "a value");
        continue;
      }
      const bool positive =
          key == "mp" || key == "mb" || key == "lp" || key == "lb" || key == "eps";
      if (key == "angle") {
        if (!std::isfinite(v.at(key))) out.emplace_back(key + id, "a finite number");
      } else {
        check(key + id, v.at(key), positive);
      }
    }
    if (v.count("mp") && v.count("lp") && v.count("mb") && v.count("lb") &&
        !(v.at("mp") * v.at("lp") > v.at("mb") * v.at("lb")))
      out.emplace_back("mp" + id, "a bottom-heavy pendulum, mp*lp > mb*lb");
  }
  for (std::size_t j = 0; j < springs.size(); ++j) {
    const auto& s = springs[j];
    const int n = static_cast<int>(metronomes.size());
    if (s.first < 0 || s.first >= n || s.second < 0 || s.second >= n || s.first == s.second)
      out.emplace_back("springs[" + std::to_string(j + 1) + "].between",
                       "two different metronomes among 1.." + std::to_string(n));
    check("kappa" + std::to_string(j + 1), s.kappa, false);
  }
  return out;
}

MetronomeModel::MetronomeModel(ModelSpec spec)
    : spec_(std::move(spec)),
      directions_(spec_.directions),
      n_metronomes_(static_cast<int>(spec_.metronomes.size())),
      represented_(n_metronomes_),
      copies_(n_metronomes_, 1.0) {
  std::iota(represented_.begin(), represented_.end(), 0);
  const auto problems = spec_.problems();
  if (!problems.empty())
    throw std::invalid_argument("invalid model: " + problems.front().first + " must be " +
                                problems.front().second);
  std::vector<double> raw{spec_.M, spec_.cx, spec_.cy, spec_.kx, spec_.ky, spec_.g};
  for (const auto& m : spec_.metronomes)
    for (const auto& key : metronome_keys())
      raw.push_back(key == "angle" ? m.values.at(key) * kDegree : m.values.at(key));
  for (const auto& s : spec_.springs) raw.push_back(s.kappa);

  std::vector<NamedParameter> named = platform_parameters(directions_);
  named.push_back({"g", {5}});
  const auto& keys = metronome_keys();
  for (int k = 0; k < kMetronomeRaw; ++k) {
    if (keys[k] == "angle") continue;
    NamedParameter shared{keys[k], {}};
    for (int i = 0; i < n_metronomes_; ++i)
      if (!spec_.metronomes[i].overridden.count(keys[k]))
        shared.raw.push_back(metronome_offset(i) + k);
    if (!shared.raw.empty()) named.push_back(shared);
  }
  for (int i = 0; i < n_metronomes_; ++i)
    for (int k = 0; k < kMetronomeRaw; ++k)
      named.push_back({keys[k] + std::to_string(i + 1),
                       {metronome_offset(i) + k},
                       keys[k] == "angle" ? kDegree : 1.0});
  NamedParameter kappa{"kappa", {}};
  for (int j = 0; j < static_cast<int>(spec_.springs.size()); ++j)
    if (!spec_.springs[j].overridden) kappa.raw.push_back(spring_offset(j));
  if (!kappa.raw.empty()) named.push_back(kappa);
  for (int j = 0; j < static_cast<int>(spec_.springs.size()); ++j)
    named.push_back({"kappa" + std::to_string(j + 1), {spring_offset(j)}});
  set_parameter_layout(std::move(named), std::move(raw));
  layout_ = low_rank_layout();
}

std::unique_ptr<OdeSystem> MetronomeModel::restricted(const InvariantSubspace& subspace) const {
  const bool already =
      std::any_of(copies_.begin(), copies_.end(), [](double c) { return c != 1.0; });
  if (already || !spec_.springs.empty() || subspace.is_whole_space()) return nullptr;
  const auto c = subspace.coordinates(dimension());
  const int D = directions_, N = n_metronomes_, m = D + N;
  // The coordinate a component is tied to (with sign +1), as a component; -1 if zero or negated.
  auto tied_to = [&](int component) {
    const int k = c.coordinate[component];
    return k < 0 || c.sign[component] != 1.0 ? -1 : c.representative[k];
  };
  for (int a = 0; a < D; ++a)
    if (tied_to(a) != a || tied_to(m + a) != m + a) return nullptr;
  std::vector<int> represented;
  std::vector<double> copies;
  std::vector<int> unit_of(N, -1);
  for (int i = 0; i < N; ++i) {
    const int angle = tied_to(D + i), velocity = tied_to(m + D + i);
    if (angle < D || angle >= m || velocity != angle + m) return nullptr;
    const int j = angle - D;  // the group's first metronome
    if (j == i) {
      unit_of[i] = static_cast<int>(represented.size());
      represented.push_back(i);
      copies.push_back(1.0);
    } else {
      copies[unit_of[j]] += 1.0;
    }
  }
  if (c.size() != 2 * (D + static_cast<int>(represented.size()))) return nullptr;
  auto model = std::make_unique<MetronomeModel>(*this);
  model->n_metronomes_ = static_cast<int>(represented.size());
  model->represented_ = std::move(represented);
  model->copies_ = std::move(copies);
  model->layout_ = model->low_rank_layout();
  return model;
}

std::vector<std::string> MetronomeModel::state_names() const {
  std::vector<std::string> names{"x"};
  if (directions_ == 2) names.push_back("y");
  for (int i = 0; i < n_metronomes_; ++i)
    names.push_back("th" + std::to_string(represented_[i] + 1));
  const int m = static_cast<int>(names.size());
  for (int i = 0; i < m; ++i) names.push_back("v" + names[i]);
  return names;
}

std::vector<SteepZone> MetronomeModel::steep_zones(const double* raw) const {
  if (spec_.escapement == Escapement::Impulsive) return {};
  std::vector<SteepZone> zones;
  for (int i = 0; i < n_metronomes_; ++i) {
    // sigma = tanh(50 th'/eps) switches within |th'| < eps/50 of a turning point.
    const double width = raw[metronome_offset(i) + 8] / 50.0;
    zones.push_back({angular_velocity_index(i), width, std::max(1.0, 10.0 * width)});
  }
  return zones;
}

int MetronomeModel::switching_count() const {
  return spec_.escapement == Escapement::Impulsive ? 5 * n_metronomes_ : 0;
}

void MetronomeModel::switching_functions(double /*t*/, const double* z, const double* raw,
                                         double* g) const {
  if (switching_count() == 0) return;  // the smooth escapements: g has no entries
  for (int i = 0; i < n_metronomes_; ++i) {
    const double ths = raw[metronome_offset(i) + 6];
    const double the = raw[metronome_offset(i) + 7];
    const double th = z[angle_index(i)];
    double* gi = g + 5 * i;
    gi[0] = z[angular_velocity_index(i)];
    gi[1] = th + ths;
    gi[2] = th - the;
    gi[3] = th + the;
    gi[4] = th - ths;
  }
}

std::string MetronomeModel::switching_name(int surface) const {
  static const char* const kLevels[] = {" = 0", " = -ths", " = the", " = -the", " = ths"};
  const int i = surface / 5, k = surface % 5;
  const auto names = state_names();
  return names.at(k == 0 ? angular_velocity_index(i) : angle_index(i)) + kLevels[k];
}

// Surface 5 i + k of metronome i is th_i' (k = 0) or th_i plus a constant (k = 1..4).
double MetronomeModel::switching_gradient(double /*t*/, const double* /*z*/, const double* /*raw*/,
                                          int surface, double* h_z) const {
  const int i = surface / 5, k = surface % 5;
  std::fill(h_z, h_z + dimension(), 0.0);
  h_z[k == 0 ? angular_velocity_index(i) : angle_index(i)] = 1.0;
  return 0.0;
}

// th + ths, th - the, th + the, th - ths: +-1 in ths (raw entry 6 of the metronome) or the (7),
// along the named parameter's direction in the raw layout.
double MetronomeModel::switching_parameter_derivative(double /*t*/, const double* /*z*/,
                                                      const double* /*raw*/, int surface,
                                                      int parameter) const {
  const int i = surface / 5, k = surface % 5;
  if (k == 0) return 0.0;
  const int entry = metronome_offset(i) + (k == 1 || k == 4 ? 6 : 7);
  const double sign = k == 1 || k == 3 ? 1.0 : -1.0;
  const auto& named = named_parameters().at(parameter);
  double derivative = 0.0;
  for (int r : named.raw)
    if (r == entry) derivative += sign * named.scale;
  return derivative;
}

std::optional<LowRankJacobian> MetronomeModel::low_rank_structure() const {
  const int D = directions_, N = n_metronomes_, m = D + N;
  std::vector<std::pair<int, int>> entries;
  for (int a = 0; a < D; ++a) entries.emplace_back(a, m + a);
  for (int i = 0; i < N; ++i) {
    entries.emplace_back(D + i, m + D + i);
    entries.emplace_back(m + D + i, D + i);
    entries.emplace_back(m + D + i, m + D + i);
  }
  for (const auto& spring : spec_.springs) {
    entries.emplace_back(m + D + spring.first, D + spring.second);
    entries.emplace_back(m + D + spring.second, D + spring.first);
  }
  return LowRankJacobian(dimension(), D, std::move(entries));
}

MetronomeModel::LowRankLayout MetronomeModel::low_rank_layout() const {
  const int D = directions_, N = n_metronomes_, m = D + N;
  const LowRankJacobian s = *low_rank_structure();
  LowRankLayout layout;
  for (int a = 0; a < D; ++a) layout.platform_velocity.push_back(s.position(a, m + a));
  for (int i = 0; i < N; ++i) {
    layout.angular_velocity.push_back(s.position(D + i, m + D + i));
    layout.own_angle.push_back(s.position(m + D + i, D + i));
    layout.own_velocity.push_back(s.position(m + D + i, m + D + i));
  }
  for (const auto& spring : spec_.springs)
    layout.spring.emplace_back(s.position(m + D + spring.first, D + spring.second),
                               s.position(m + D + spring.second, D + spring.first));
  return layout;
}

// The same quantities as evaluate(), in doubles, with their derivatives by hand: G_i, b_i and F
// depend on metronome i's own angle and velocity (G_i also on its spring partners' angles), so
// every derivative of r'' = Sigma^{-1} (F - R), Sigma = Mt - A, is a sum over metronomes:
//   d r'' = Sigma^{-1} (dF - dR + dA r'').
bool MetronomeModel::low_rank_jacobian(double /*t*/, const double* z, const double* raw,
                                       LowRankJacobian& out) const {
  const int D = directions_, N = n_metronomes_, m = D + N, n = dimension();
  if (out.dimension != n || out.rank() != D ||
      out.nonzeros() != static_cast<int>(out.values.size()) || out.W.rows() != n ||
      out.W.cols() != D)
    throw std::invalid_argument("MetronomeModel::low_rank_jacobian: not the model's structure");
  const double g = raw[5];

  thread_local std::vector<double> torque, G, G_angle, G_velocity, inertia, p, sn, cs;
  thread_local std::vector<std::array<double, 2>> e;
  for (auto* v : {&torque, &G, &G_angle, &G_velocity, &inertia, &p, &sn, &cs}) v->assign(N, 0.0);
  e.assign(N, {0.0, 0.0});
  for (int j = 0; j < static_cast<int>(spec_.springs.size()); ++j) {
    const auto& spring = spec_.springs[j];
    const double q = raw[spring_offset(j)] * (z[D + spring.first] - z[D + spring.second]);
    torque[spring.first] += q;
    torque[spring.second] -= q;
  }

  double Mt = raw[0];
  double F[2] = {0.0, 0.0}, A[2][2] = {{0.0, 0.0}, {0.0, 0.0}}, R[2] = {0.0, 0.0};
  for (int a = 0; a < D; ++a) F[a] = -raw[1 + a] * z[m + a] - raw[3 + a] * z[a];
  for (int i = 0; i < N; ++i) {
    const double* mi = raw + metronome_offset(i);
    const double copies = copies_[i];
    Mt += copies * (mi[0] + mi[1]);
    p[i] = mi[0] * mi[2] - mi[1] * mi[3];
    inertia[i] = mi[0] * mi[2] * mi[2] + mi[1] * mi[3] * mi[3];
    e[i] = {std::cos(mi[9]), std::sin(mi[9])};
    const double th = z[D + i], w = z[m + D + i];
    sn[i] = std::sin(th);
    cs[i] = std::cos(th);
    Dual<2> th_d(th), w_d(w);
    th_d.d[0] = 1.0;
    w_d.d[1] = 1.0;
    const Dual<2> u = escapement(th_d, w_d, mi);
    G[i] = u.v - mi[4] * w - p[i] * g * sn[i] - torque[i];
    G_angle[i] = u.d[0] - p[i] * g * cs[i];  // without the springs
    G_velocity[i] = u.d[1] - mi[4];
    for (int a = 0; a < D; ++a) {
      const double ba = p[i] * cs[i] * e[i][a];
      F[a] += copies * p[i] * w * w * sn[i] * e[i][a];
      R[a] += copies * ba * G[i] / inertia[i];
      for (int c = 0; c < D; ++c) A[a][c] += copies * ba * p[i] * cs[i] * e[i][c] / inertia[i];
    }
  }

  // Sigma^{-1} and r''.
  double Si[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
  if (D == 1) {
    Si[0][0] = 1.0 / (Mt - A[0][0]);
  } else {
    const double s00 = Mt - A[0][0], s01 = -A[0][1], s11 = Mt - A[1][1];
    const double det = s00 * s11 - s01 * s01;
    Si[0][0] = s11 / det;
    Si[0][1] = Si[1][0] = -s01 / det;
    Si[1][1] = s00 / det;
  }
  double acc[2] = {0.0, 0.0};
  for (int a = 0; a < D; ++a)
    for (int c = 0; c < D; ++c) acc[a] += Si[a][c] * (F[c] - R[c]);

  // S and U.
  std::fill(out.values.begin(), out.values.end(), 0.0);
  out.U.setZero();
  for (int a = 0; a < D; ++a) {
    out.values[layout_.platform_velocity[a]] = 1.0;
    out.U(m + a, a) = 1.0;
  }
  for (int i = 0; i < N; ++i) {
    double e_acc = 0.0;
    for (int a = 0; a < D; ++a) e_acc += e[i][a] * acc[a];
    out.values[layout_.angular_velocity[i]] = 1.0;
    out.values[layout_.own_angle[i]] = (G_angle[i] + p[i] * sn[i] * e_acc) / inertia[i];
    out.values[layout_.own_velocity[i]] = G_velocity[i] / inertia[i];
    for (int a = 0; a < D; ++a) out.U(m + D + i, a) = -p[i] * cs[i] * e[i][a] / inertia[i];
  }

  // Y = dF - dR + dA r'' (D x n, one column per state), then W^T = Sigma^{-1} Y.
  thread_local Eigen::MatrixXd Y;
  Y.setZero(D, n);
  for (int a = 0; a < D; ++a) {
    Y(a, a) = -raw[3 + a];
    Y(a, m + a) = -raw[1 + a];
  }
  for (int i = 0; i < N; ++i) {
    const double w = z[m + D + i];
    double b_acc = 0.0, db_acc = 0.0;  // b_i . r'' and (db_i/dth_i) . r''
    for (int a = 0; a < D; ++a) {
      b_acc += p[i] * cs[i] * e[i][a] * acc[a];
      db_acc -= p[i] * sn[i] * e[i][a] * acc[a];
    }
    for (int a = 0; a < D; ++a) {
      const double b = p[i] * cs[i] * e[i][a], db = -p[i] * sn[i] * e[i][a];
      Y(a, D + i) =
          copies_[i] * (p[i] * w * w * cs[i] * e[i][a] - (db * G[i] + b * G_angle[i]) / inertia[i] +
                        (db * b_acc + b * db_acc) / inertia[i]);
      Y(a, m + D + i) =
          copies_[i] * (2.0 * p[i] * w * sn[i] * e[i][a] - b * G_velocity[i] / inertia[i]);
    }
  }
  for (int j = 0; j < static_cast<int>(spec_.springs.size()); ++j) {
    const auto& spring = spec_.springs[j];
    const int f = spring.first, s = spring.second;
    const double kappa = raw[spring_offset(j)];
    out.values[layout_.own_angle[f]] -= kappa / inertia[f];
    out.values[layout_.own_angle[s]] -= kappa / inertia[s];
    out.values[layout_.spring[j].first] += kappa / inertia[f];
    out.values[layout_.spring[j].second] += kappa / inertia[s];
    for (int a = 0; a < D; ++a) {
      const double bf = p[f] * cs[f] * e[f][a] / inertia[f];
      const double bs = p[s] * cs[s] * e[s][a] / inertia[s];
      Y(a, D + f) += kappa * (bf - bs);
      Y(a, D + s) += kappa * (bs - bf);
    }
  }
  for (int a = 0; a < D; ++a)
    for (int k = 0; k < n; ++k) {
      double sum = 0.0;
      for (int c = 0; c < D; ++c) sum += Si[a][c] * Y(c, k);
      out.W(k, a) = sum;
    }
  return true;
}

double MetronomeModel::total_mass(const ParameterValues& raw) const {
  double Mt = raw[0];
  for (int i = 0; i < n_metronomes_; ++i)
    Mt += copies_[i] * (raw[metronome_offset(i)] + raw[metronome_offset(i) + 1]);
  return Mt;
}

double MetronomeModel::mechanical_energy(const Eigen::VectorXd& z,
                                         const ParameterValues& raw) const {
  const int D = directions_;
  const int m = D + n_metronomes_;
  double energy = 0.0;
  double v2 = 0.0;
  for (int a = 0; a < D; ++a) {
    v2 += z[m + a] * z[m + a];
    energy += 0.5 * raw[3 + a] * z[a] * z[a];
  }
  energy += 0.5 * total_mass(raw) * v2;
  for (int i = 0; i < n_metronomes_; ++i) {
    const double* mi = raw.data() + metronome_offset(i);
    const double p = mi[0] * mi[2] - mi[1] * mi[3];
    const double I = mi[0] * mi[2] * mi[2] + mi[1] * mi[3] * mi[3];
    const double th = z[D + i], w = z[m + D + i];
    double e_dot_v = z[m] * std::cos(mi[9]);
    if (D == 2) e_dot_v += z[m + 1] * std::sin(mi[9]);
    energy += copies_[i] * (0.5 * I * w * w + p * std::cos(th) * w * e_dot_v +
                            p * raw[5] * (1.0 - std::cos(th)));
  }
  for (int j = 0; j < static_cast<int>(spec_.springs.size()); ++j) {
    const auto& s = spec_.springs[j];
    const double dth = z[D + s.first] - z[D + s.second];
    energy += 0.5 * raw[spring_offset(j)] * dth * dth;
  }
  return energy;
}

}  // namespace sympathy
