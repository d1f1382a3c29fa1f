#include "sympathy/cases/metronome_model.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <random>
#include <unsupported/Eigen/MatrixFunctions>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/reduced_system.hpp"
#include "tests/support/cases.hpp"

namespace sympathy {
namespace {

using testing::case_path;
using testing::load_spec;
using testing::random_state;

Eigen::MatrixXd finite_difference_jacobian(const OdeSystem& s, const Eigen::VectorXd& z,
                                           const ParameterValues& p) {
  const int n = s.dimension();
  Eigen::MatrixXd j(n, n);
  for (int c = 0; c < n; ++c) {
    const double h = 1e-7 * std::max(1.0, std::abs(z[c]));
    Eigen::VectorXd zp = z, zm = z;
    zp[c] += h;
    zm[c] -= h;
    j.col(c) = (s.rhs(0.0, zp, p) - s.rhs(0.0, zm, p)) / (2 * h);
  }
  return j;
}

struct Setup {
  std::string name;
  Escapement escapement;
};

void PrintTo(const Setup& s, std::ostream* os) {
  *os << s.name << " " << to_string(s.escapement);
}

class EverySetup : public ::testing::TestWithParam<Setup> {};

// df/dz from dual numbers against central differences, at random states and at states inside
// the escapement's switching band (|th'| < eps/50), where f is steepest.
TEST_P(EverySetup, JacobianMatchesFiniteDifferences) {
  const MetronomeModel model(load_spec(GetParam().name, "", GetParam().escapement));
  const ParameterValues values = model.default_parameters();
  std::mt19937 rng(7);
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::VectorXd z = random_state(model, rng);
    if (trial >= 4)  // inside the band: sigma = tanh(1000 th') is mid-switch
      for (int i = 0; i < model.metronome_count(); ++i)
        z[model.angular_velocity_index(i)] = 2e-4 * (i + 1) * (trial == 4 ? 1 : -1);
    const Eigen::MatrixXd exact = model.jacobian(0.0, z, values);
    const Eigen::MatrixXd fd = finite_difference_jacobian(model, z, values);
    EXPECT_LT((exact - fd).cwiseAbs().maxCoeff(), 1e-6 * exact.cwiseAbs().maxCoeff())
        << GetParam().name << " trial " << trial;
  }
}

// df/dp for every named parameter against central differences in that parameter.
TEST_P(EverySetup, ParameterDerivativesMatchFiniteDifferences) {
  const MetronomeModel model(load_spec(GetParam().name, "", GetParam().escapement));
  const ParameterValues values = model.default_parameters();
  std::mt19937 rng(11);
  const Eigen::VectorXd z = random_state(model, rng);
  const auto names = model.parameter_names();
  for (int p = 0; p < static_cast<int>(names.size()); ++p) {
    const double v = model.parameter(values, p);
    const double h = 1e-4 * std::max(std::abs(v), 1e-3);
    const Eigen::VectorXd fp = model.rhs(0.0, z, model.with_parameter(values, p, v + h));
    const Eigen::VectorXd fm = model.rhs(0.0, z, model.with_parameter(values, p, v - h));
    const Eigen::VectorXd fd = (fp - fm) / (2 * h);
    Eigen::VectorXd exact(model.dimension());
    model.parameter_derivative(0.0, z.data(), values.data(), p, exact.data());
    // Truncation error ~ (h/p)^2 relative; roundoff ~ 1e-15 |f| / h.
    const double roundoff = 1e-15 * fp.cwiseAbs().maxCoeff() / h;
    EXPECT_LE((exact - fd).cwiseAbs().maxCoeff(), 1e-6 * exact.cwiseAbs().maxCoeff() + roundoff)
        << GetParam().name << " parameter " << names[p];
  }
}

// The sensitivity right-hand side: J*S for state columns, J*s + df/dp for parameter columns.
TEST_P(EverySetup, VariationalRhsIsJacobianTimesColumns) {
  const MetronomeModel model(load_spec(GetParam().name, "", GetParam().escapement));
  const ParameterValues values = model.default_parameters();
  std::mt19937 rng(3);
  const Eigen::VectorXd z = random_state(model, rng);
  const int n = model.dimension();
  const std::vector<int> params{model.parameter_index("k"), model.parameter_index("d")};
  const int columns = n + 2;
  Eigen::MatrixXd S = Eigen::MatrixXd::Random(n, columns), out(n, columns);
  std::vector<const double*> in_ptr(columns);
  std::vector<double*> out_ptr(columns);
  for (int j = 0; j < columns; ++j) {
    in_ptr[j] = S.col(j).data();
    out_ptr[j] = out.col(j).data();
  }
  model.variational_rhs(0.0, z.data(), values.data(), columns, in_ptr.data(), out_ptr.data(),
                        params);
  const Eigen::MatrixXd J = model.jacobian(0.0, z, values);
  Eigen::MatrixXd expected = J * S;
  for (int k = 0; k < 2; ++k) {
    Eigen::VectorXd dfdp(n);
    model.parameter_derivative(0.0, z.data(), values.data(), params[k], dfdp.data());
    expected.col(n + k) += dfdp;
  }
  EXPECT_LT((out - expected).cwiseAbs().maxCoeff(), 1e-12 * expected.cwiseAbs().maxCoeff());
}

// f and the columns in one call (OdeSystem::rhs_and_variational, what the augmented flows and the
// across block call every step): f read off the dual numbers' values is rhs's f to rounding (the
// dual operations reach the same values by other roundings: measured at most 1.6e-16 of |f|_inf),
// and the columns are variational_rhs's bit for bit, for every count of state columns (1 to n, so
// each dual width, and none) with and without parameter columns.
TEST_P(EverySetup, RhsAndVariationalInOneCallIsBothCalls) {
  const MetronomeModel model(load_spec(GetParam().name, "", GetParam().escapement));
  const ParameterValues values = model.default_parameters();
  std::mt19937 rng(5);
  const Eigen::VectorXd z = random_state(model, rng);
  const int n = model.dimension();
  const Eigen::VectorXd f = model.rhs(0.0, z, values);
  for (const std::vector<int>& params :
       {std::vector<int>{}, std::vector<int>{model.parameter_index("k")}})
    for (int state_columns = 0; state_columns <= n; ++state_columns) {
      const int columns = state_columns + static_cast<int>(params.size());
      Eigen::MatrixXd S = Eigen::MatrixXd::Random(n, std::max(columns, 1));
      Eigen::MatrixXd expected(n, std::max(columns, 1)), out(n, std::max(columns, 1));
      std::vector<const double*> in_ptr(columns);
      std::vector<double*> expected_ptr(columns), out_ptr(columns);
      for (int j = 0; j < columns; ++j) {
        in_ptr[j] = S.col(j).data();
        expected_ptr[j] = expected.col(j).data();
        out_ptr[j] = out.col(j).data();
      }
      if (columns > 0)
        model.variational_rhs(0.0, z.data(), values.data(), columns, in_ptr.data(),
                              expected_ptr.data(), params);
      Eigen::VectorXd dz(n);
      model.rhs_and_variational(0.0, z.data(), values.data(), dz.data(), columns, in_ptr.data(),
                                out_ptr.data(), params);
      EXPECT_LE((dz - f).cwiseAbs().maxCoeff(), 4e-16 * f.cwiseAbs().maxCoeff())
          << state_columns << " state columns";
      for (int j = 0; j < columns; ++j)
        EXPECT_EQ(out.col(j), expected.col(j)) << state_columns << " state columns, column " << j;
    }
}

INSTANTIATE_TEST_SUITE_P(
    Cases, EverySetup,
    ::testing::Values(Setup{"row2", Escapement::Half}, Setup{"row2", Escapement::Double},
                      Setup{"cross4", Escapement::Half}, Setup{"cross4", Escapement::Double},
                      Setup{"cross4_spring", Escapement::Half},
                      Setup{"cross4_spring", Escapement::Double}),
    [](const auto& info) { return info.param.name + "_" + to_string(info.param.escapement); });

// Escapement torque u(th, th') of eq. 3 as written in MODEL.md, evaluated here independently.
double half_escapement(double th, double w, double s, double ths, double the, double eps) {
  const double sigma = std::tanh(50 * w / eps);
  return s * sigma * (std::tanh((sigma * th + ths) / eps) - std::tanh((sigma * th - the) / eps)) /
         2;
}

// The accelerations against a dense solve of the paper's equations, written out here in the
// paper's own form: eq. 4 (row), eq. 7-10 (cross, r = sqrt(2)/2), eq. 11-15 (virtual spring).
TEST(MetronomeModel, AccelerationsMatchPaperEquations) {
  const double r = std::sqrt(2.0) / 2.0;
  for (const std::string name : {"row2", "cross4", "cross4_spring"}) {
    const ModelSpec spec = load_spec(name);
    MetronomeModel model(spec);
    const auto& m = spec.metronomes[0].values;
    const double mp = m.at("mp"), mb = m.at("mb"), lp = m.at("lp"), lb = m.at("lb");
    const double p = mp * lp - mb * lb, I = mp * lp * lp + mb * lb * lb;
    const int N = model.metronome_count(), D = model.platform_directions(), q = D + N;
    const double Mt = spec.M + N * (mp + mb);
    std::mt19937 rng(5);
    const Eigen::VectorXd z = random_state(model, rng);
    // Unknowns (x'', [y''], th_i''); rows: platform equations then metronome equations.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(q, q);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(q);
    // Coupling coefficient of metronome i in each platform direction (e_i, paper form).
    auto coupling = [&](int i, int a) {
      if (name == "row2") return 1.0;
      if (name == "cross4_spring") return r;
      return a == 0 ? r : (i < 2 ? r : -r);  // cross: x: +r all; y: +r for 1,2 and -r for 3,4
    };
    for (int a = 0; a < D; ++a) {
      A(a, a) = Mt;
      b[a] = -spec.cx * z[q + a] - spec.kx * z[a];
      for (int i = 0; i < N; ++i) {
        const double th = z[D + i], w = z[q + D + i];
        A(a, D + i) = p * coupling(i, a) * std::cos(th);  // p e_i th'' cos(th)
        b[a] += p * coupling(i, a) * w * w * std::sin(th);
      }
    }
    for (int i = 0; i < N; ++i) {
      const double th = z[D + i], w = z[q + D + i];
      A(D + i, D + i) = I;
      for (int a = 0; a < D; ++a) A(D + i, a) = p * coupling(i, a) * std::cos(th);
      double spring = 0.0;
      if (name == "cross4_spring" && (i == 0 || i == 2)) {
        const double kappa = spec.springs[0].kappa;
        spring = (i == 0 ? 1.0 : -1.0) * kappa * (z[D + 0] - z[D + 2]);
      }
      b[D + i] = half_escapement(th, w, m.at("s"), m.at("ths"), m.at("the"), m.at("eps")) -
                 m.at("d") * w - p * spec.g * std::sin(th) - spring;
    }
    const Eigen::VectorXd acc = A.partialPivLu().solve(b);
    const Eigen::VectorXd f = model.rhs(0.0, z, model.default_parameters());
    EXPECT_LT((f.tail(q) - acc).cwiseAbs().maxCoeff(), 1e-12 * acc.cwiseAbs().maxCoeff()) << name;
    EXPECT_EQ(f.head(q), z.tail(q)) << name;
  }
}

// The escapement's plateaus (MODEL.md): "half" gives s inside the window, "double" about 2s
// (tanh(ths/2e) + tanh(the/2e) = 1.951 for Table I), "impulsive" exactly +-s inside and 0
// outside its window. Read off th'' of one metronome on a platform too heavy to move.
TEST(MetronomeModel, EscapementForms) {
  for (Escapement form : {Escapement::Half, Escapement::Double, Escapement::Impulsive}) {
    ModelSpec spec = load_spec("row2", "", form);
    spec.metronomes.resize(1);
    spec.M = 1e12;
    MetronomeModel model(spec);
    const auto& m = spec.metronomes[0].values;
    const double s = m.at("s"), ths = m.at("ths"), the = m.at("the"), eps = m.at("eps");
    const double I = m.at("mp") * m.at("lp") * m.at("lp") + m.at("mb") * m.at("lb") * m.at("lb");
    const double d = m.at("d"), p = m.at("mp") * m.at("lp") - m.at("mb") * m.at("lb");
    auto torque = [&](double th, double w) {
      Eigen::VectorXd z(4);
      z << 0.0, th, 0.0, w;
      return model.rhs(0.0, z, model.default_parameters())[3] * I + d * w +
             p * spec.g * std::sin(th);
    };
    struct Point {
      double th, w;
    };
    for (Point pt : {Point{0.0, 1.0}, Point{0.0, -1.0}, Point{0.25, 1.0}, Point{0.25, -1.0},
                     Point{-0.25, 1.0}, Point{0.5, 0.5}, Point{0.1, 1e-4}}) {
      double expected = 0.0;
      if (form == Escapement::Half) {
        expected = half_escapement(pt.th, pt.w, s, ths, the, eps);
      } else if (form == Escapement::Double) {
        const double sigma = std::tanh(50 * pt.w / eps);
        expected = s * sigma *
                   (std::tanh((sigma * pt.th + ths) / (2 * eps)) -
                    std::tanh((sigma * pt.th - the) / (2 * eps)));
      } else {
        if (pt.w > 0 && pt.th >= -ths && pt.th <= the) expected = s;
        if (pt.w < 0 && pt.th >= -the && pt.th <= ths) expected = -s;
      }
      EXPECT_NEAR(torque(pt.th, pt.w), expected, 1e-9 * s)
          << to_string(form) << " th " << pt.th << " w " << pt.w;
    }
    if (form == Escapement::Half) {
      EXPECT_NEAR(torque(0.0, 1.0), s, 1e-3 * s);
    } else if (form == Escapement::Double) {
      EXPECT_NEAR(torque(0.0, 1.0), 1.951 * s, 1e-3 * s);
    }
    // Every escapement has derivatives between switching surfaces; the impulsive one has surfaces.
    EXPECT_TRUE(model.differentiable());
    EXPECT_EQ(model.switching_count() > 0, form == Escapement::Impulsive);
  }
}

// With d = s = c = 0 (and the virtual spring's energy counted) the total mechanical energy is
// a constant of motion; it drifts only by the integration error, which falls with the
// tolerance. BDF damps oscillations numerically, so its drift is larger (measured over 20 s at
// rtol 1e-11: BDF 3e-8 (row2) to 2e-7 (spring), Adams 2e-9 to 6e-10).
TEST(MetronomeModel, EnergyIsConservedWithoutDampingOrDrive) {
  for (const std::string name : {"row2", "cross4", "cross4_spring"}) {
    ModelSpec spec = load_spec(name);
    spec.set("d", 0.0);
    spec.set("s", 0.0);
    spec.set("c", 0.0);
    MetronomeModel model(spec);
    Eigen::VectorXd z0 = Eigen::VectorXd::Zero(model.dimension());
    for (int i = 0; i < model.metronome_count(); ++i) z0[model.angle_index(i)] = 0.5 - 0.3 * i;
    const ParameterValues values = model.default_parameters();
    const double e0 = model.mechanical_energy(z0, values);
    for (Method method : {Method::Adams, Method::BDF}) {
      FlowOptions o;
      o.method = method;
      o.nonlinear_solver =
          method == Method::BDF ? NonlinearSolver::Newton : NonlinearSolver::FixedPoint;
      o.rtol = 1e-11;
      o.atol = 1e-13;
      Flow flow(model, o);
      const Eigen::VectorXd z = flow.advance(z0, values, 0.0, 20.0);
      const double bound = method == Method::Adams ? 1e-8 : 1e-6;
      EXPECT_LT(std::abs(model.mechanical_energy(z, values) - e0), bound * e0)
          << name << " " << to_string(method);
      EXPECT_GT((z - z0).norm(), 0.1) << name;  // it did move
    }
  }
}

// Small swings with s = 0 follow the linearized equations M q'' + C q' + K q = 0, with the
// mass, damping and stiffness matrices written out from eq. 4 at th = 0: z(t) = expm(A t) z0.
// The nonlinear terms are of relative size th^2 = 1e-8 at th = 1e-4.
TEST(MetronomeModel, SmallAnglesFollowLinearizedAnalyticSolution) {
  ModelSpec spec = load_spec("row2");
  spec.set("s", 0.0);
  MetronomeModel model(spec);
  const auto& m = spec.metronomes[0].values;
  const double p = m.at("mp") * m.at("lp") - m.at("mb") * m.at("lb");
  const double I = m.at("mp") * m.at("lp") * m.at("lp") + m.at("mb") * m.at("lb") * m.at("lb");
  const ParameterValues values = model.default_parameters();
  const double Mt = model.total_mass(values);
  Eigen::Matrix3d M, C, K;
  M << Mt, p, p, p, I, 0, p, 0, I;
  C = Eigen::Vector3d(spec.cx, m.at("d"), m.at("d")).asDiagonal();
  K = Eigen::Vector3d(spec.kx, p * spec.g, p * spec.g).asDiagonal();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 6);
  A.topRightCorner(3, 3).setIdentity();
  A.bottomLeftCorner(3, 3) = -M.inverse() * K;
  A.bottomRightCorner(3, 3) = -M.inverse() * C;
  Eigen::VectorXd z0(6);
  z0 << 0.0, 1e-4, -0.6e-4, 0.0, 0.0, 0.0;
  FlowOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-16;
  Flow flow(model, o);
  for (double t : {0.3, 2.0, 7.5}) {
    const Eigen::VectorXd exact = (A * t).exp() * z0;
    const Eigen::VectorXd z = flow.advance(z0, values, 0.0, t);
    for (int i = 0; i < 6; ++i)
      EXPECT_LT(std::abs(z[i] - exact[i]),
                1e-6 * exact.segment(3 * (i / 3), 3).cwiseAbs().maxCoeff())
          << "t " << t << " component " << i;
  }
}

// Named parameters: shared names move every metronome that does not override them; a
// per-metronome name moves one; "c" on a 2-D platform moves cx and cy, so df/dc is their sum.
TEST(MetronomeModel, NamedParameters) {
  ModelSpec spec = load_spec("cross4");
  spec.set("d3", 5e-6);  // metronome 3 detuned in damping
  const MetronomeModel model(spec);
  const auto names = model.parameter_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "d"), names.end());
  EXPECT_NE(std::find(names.begin(), names.end(), "angle4"), names.end());
  auto index = [&](const char* name) { return model.parameter_index(name); };
  ParameterValues values = model.default_parameters();
  EXPECT_NEAR(model.parameter(values, index("angle3")), -45.0, 1e-12);
  model.set_parameter(values, index("d"), 1e-6);
  EXPECT_EQ(model.parameter(values, index("d1")), 1e-6);
  EXPECT_EQ(model.parameter(values, index("d3")), 5e-6);
  std::mt19937 rng(2);
  const Eigen::VectorXd z = random_state(model, rng);
  Eigen::VectorXd dc(model.dimension()), dcx(model.dimension()), dcy(model.dimension());
  model.parameter_derivative(0.0, z.data(), values.data(), index("c"), dc.data());
  model.parameter_derivative(0.0, z.data(), values.data(), index("cx"), dcx.data());
  model.parameter_derivative(0.0, z.data(), values.data(), index("cy"), dcy.data());
  EXPECT_LT((dc - dcx - dcy).cwiseAbs().maxCoeff(), 1e-14 * dc.cwiseAbs().maxCoeff());
  EXPECT_THROW(model.parameter_index("nonsense"), std::invalid_argument);
  const auto states = model.state_names();
  EXPECT_EQ(states, (std::vector<std::string>{"x", "y", "th1", "th2", "th3", "th4", "vx", "vy",
                                              "vth1", "vth2", "vth3", "vth4"}));
}

// NUMERICS.md: stepping over the escapement pulse at each turning point leaves an error of
// about 3e-7 in the state after one period whatever the tolerance. Resolved, the error falls
// with the tolerance (measured here: 3e-6, 9e-8, 1.6e-9 at rtol 1e-8, 1e-10, 1e-12 over two
// periods). Reference: rtol 1e-12 with a 1e-5 s step cap, which agrees with a 2e-5 s cap to 1e-10.
TEST(MetronomeModel, TurningPointPulseIsResolved) {
  MetronomeModel model(load_spec("row2"));
  Eigen::VectorXd z0(6);
  z0 << 0.0, 0.7, 0.65, 0.0, 0.0, 0.0;
  auto run = [&](double rtol, double max_step, bool resolve) {
    FlowOptions o;
    o.rtol = rtol;
    o.atol = rtol * 1e-2;
    o.max_step = max_step;
    o.resolve_steep_zones = resolve;
    Flow flow(model, o);
    return flow.advance(z0, model.default_parameters(), 0.0, 1.2);
  };
  const Eigen::VectorXd exact = run(1e-12, 1e-5, true);
  EXPECT_LT((run(1e-12, 2e-5, true) - exact).cwiseAbs().maxCoeff(), 1e-10);
  const double bounds[] = {1e-5, 3e-7, 1e-8};
  const double rtols[] = {1e-8, 1e-10, 1e-12};
  for (int k = 0; k < 3; ++k)
    EXPECT_LT((run(rtols[k], 0.0, true) - exact).cwiseAbs().maxCoeff(), bounds[k])
        << "rtol " << rtols[k];
  // With a 1e-4 s step cap at rtol 1e-8 the two answers differ: stepped over, the pulse leaves
  // a micro-scale error; resolved, the error is at the tolerance.
  EXPECT_GT((run(1e-8, 1e-4, false) - exact).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_LT((run(1e-8, 1e-4, true) - exact).cwiseAbs().maxCoeff(), 1e-7);
}

// Eight identical metronomes, restricted to where metronomes 2-8 move alike: the model's own
// restriction (a platform with two metronomes, the second counted seven times) is the generic
// one (the whole model evaluated on the embedded state), to rounding, in f, its Jacobian (dense
// and sparse plus low rank), its variational and parameter columns, and its steep zones.
TEST(MetronomeModel, RestrictionToIdenticalMetronomesIsTheGenericOne) {
  for (int directions : {1, 2}) {
    ModelSpec spec = load_spec("row/row8");
    if (directions == 2) {
      spec.directions = 2;
      spec.cy = spec.cx;
      spec.ky = spec.kx;
    }
    const MetronomeModel model(spec);
    const int n = model.dimension(), m = n / 2, D = directions;
    std::vector<ComponentRelation> relations;
    for (int i = 2; i < 8; ++i) {
      relations.push_back({D + i, D + 1, 1.0});
      relations.push_back({m + D + i, m + D + 1, 1.0});
    }
    const InvariantSubspace block(n, relations);
    const auto own = model.restricted(block);
    ASSERT_NE(own, nullptr);
    const ReducedSystem generic(model, block);
    ASSERT_EQ(own->dimension(), 2 * (D + 2));
    EXPECT_EQ(own->state_names(), generic.state_names());
    EXPECT_EQ(own->parameter_names(), model.parameter_names());
    std::mt19937 rng(5);
    const ParameterValues p = model.default_parameters();
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd y =
          generic.coordinates().restrict(block.project(random_state(model, rng)));
      const Eigen::VectorXd f = generic.rhs(0.0, y, p);
      EXPECT_LT((own->rhs(0.0, y, p) - f).cwiseAbs().maxCoeff(), 1e-13 * f.cwiseAbs().maxCoeff());
      const Eigen::MatrixXd J = generic.jacobian(0.0, y, p);
      const double scale = J.cwiseAbs().maxCoeff();
      EXPECT_LT((own->jacobian(0.0, y, p) - J).cwiseAbs().maxCoeff(), 1e-12 * scale);
      auto low_rank = own->low_rank_structure();
      ASSERT_TRUE(low_rank.has_value());
      ASSERT_TRUE(own->low_rank_jacobian(0.0, y.data(), p.data(), *low_rank));
      EXPECT_LT((low_rank->dense() - J).cwiseAbs().maxCoeff(), 1e-12 * scale);
      for (const std::string name : {"k", "s", "M"}) {
        const int k = model.parameter_index(name);
        Eigen::VectorXd a(y.size()), b(y.size());
        own->parameter_derivative(0.0, y.data(), p.data(), k, a.data());
        generic.parameter_derivative(0.0, y.data(), p.data(), k, b.data());
        EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-12 * std::max(1.0, b.cwiseAbs().maxCoeff()))
            << name;
      }
    }
    ASSERT_EQ(own->steep_zones(p.data()).size(), 2u);
    EXPECT_EQ(own->steep_zones(p.data())[1].component, generic.steep_zones(p.data())[1].component);
  }
  // Anything but whole metronomes tied together has no restriction of the model's own.
  const MetronomeModel row2(load_spec("row2"));
  EXPECT_EQ(row2.restricted(
                InvariantSubspace(6, {{0, -1, 1.0}, {2, 1, -1.0}, {3, -1, 1.0}, {5, 4, -1.0}})),
            nullptr);
  EXPECT_EQ(row2.restricted(InvariantSubspace(6, {{2, 1, 1.0}})), nullptr);  // angles alone
}

}  // namespace
}  // namespace sympathy
