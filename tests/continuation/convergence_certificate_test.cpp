// The convergence certificate (convergence_certificate.hpp) on normal forms whose trajectories
// are known in closed form: the Hopf form's returns to its circle, and the Bautin form's unstable
// small cycle, near which a trajectory lingers before it goes to the large one.
#include "sympathy/continuation/convergence_certificate.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sympathy/core/autodiff_system.hpp"
#include "sympathy/core/flow.hpp"
#include "tests/support/test_systems.hpp"

namespace sympathy {
namespace {

// In x, y: r' = r g, theta' = 1 with g = b1 - r^2 (the Hopf form, mu = b1) or, `quintic`,
// g = b1 + b2 r^2 - r^4 (the Bautin form).
class RadialForm final : public AutoDiffSystem<RadialForm> {
 public:
  explicit RadialForm(bool quintic) : quintic_(quintic) {
    set_parameter_layout({{"b1", {0}}, {"b2", {1}}}, {0.25, 0.0});
  }
  int dimension() const override { return 2; }
  std::vector<std::string> state_names() const override { return {"x", "y"}; }
  template <class T, class P>
  void evaluate(double, const T* z, const P* p, T* dz) const {
    const T r2 = z[0] * z[0] + z[1] * z[1];
    const T g = quintic_ ? T(p[0] + p[1] * r2 - r2 * r2) : T(p[0] - r2);
    dz[0] = g * z[0] - z[1];
    dz[1] = g * z[1] + z[0];
  }

 private:
  bool quintic_;
};

PeriodicOrbit orbit_at(const OdeSystem& system, const ParameterValues& p, double r) {
  OrbitOptions options;
  const PeriodicOrbit orbit =
      solve_periodic_orbit(system, p, Eigen::Vector2d(r, 0.0), 2 * M_PI, {}, options);
  EXPECT_TRUE(orbit.converged());
  return orbit;
}

// The Hopf form at mu = 0.25: the circle r = 1/2, period 2 pi, multiplier exp(-4 pi mu) = e^-pi.
// From r0 = 0.8 every return to the section through z* (a ray: the section is normal to the
// flow) is one period later, at r_k^2 = mu / (1 + (mu / r0^2 - 1) e^(-2 mu t_k)), so its
// distance is |r_k - 1/2| |cos|/sin of z*'s angle| / (1/2) (each state's amplitude 1/2): each
// to 1e-7 (rtol 1e-8, Hermite at dt = 0.01): the radial eigenvector's coordinate. Certified at
// the first return k (from 4 on) whose last five distances are below the radius (0.25), each at
// most rho + (1 - rho) / 2 times the one before (from the closed form).
TEST(ConvergenceCertificate, HopfReturnsOnTheirClosedForm) {
  const RadialForm system(false);
  const ParameterValues p = system.default_parameters();
  const PeriodicOrbit orbit = orbit_at(system, p, 0.5);
  ConvergenceCertificate certificate(system, std::make_shared<OrbitNeighbourhood>(system, orbit));
  ASSERT_TRUE(certificate.eligible());
  EXPECT_NEAR(certificate.rate(), std::exp(-M_PI), 1e-8);
  const double theta = std::atan2(orbit.state0[1], orbit.state0[0]);
  const double r0 = 0.8, mu = 0.25;
  Flow flow(system);
  std::vector<double> times;
  for (int i = 0; i <= 6000; ++i) times.push_back(0.01 * i);
  double certified_at = -1.0;
  flow.sample(Eigen::Vector2d(r0, 0.0), p, 0.0, times, [&](double t, const Eigen::VectorXd& z) {
    if (certificate.add(t, z) && certified_at < 0) certified_at = t;
  });
  const auto& d = certificate.distances();
  const auto& t = certificate.return_times();
  ASSERT_GE(d.size(), 8u);
  const double rho = std::exp(-M_PI);
  int expected = -1;
  for (std::size_t k = 0; k < d.size(); ++k) {
    // The angle grows at 1: the k-th return at theta (mod 2 pi), one period after the last (the
    // start itself, on the section when theta = 0, is no return).
    double first = std::fmod(theta + 2 * M_PI, 2 * M_PI);
    if (first < 1e-9) first += 2 * M_PI;
    const double tk = first + 2 * M_PI * k;
    EXPECT_NEAR(t[k], tk, 1e-7) << k;
    const double r = std::sqrt(mu / (1 + (mu / (r0 * r0) - 1) * std::exp(-2 * mu * tk)));
    const double exact =
        std::abs(r - 0.5) * std::max(std::abs(std::cos(theta)), std::abs(std::sin(theta))) / 0.5;
    EXPECT_NEAR(d[k], exact, 1e-7) << k;
    if (expected < 0 && k >= 4) {
      bool near = d[k - 4] < 0.25;
      for (std::size_t j = k - 3; j <= k; ++j)
        near = near && d[j] < 0.25 && d[j] <= (rho + 0.5 * (1 - rho)) * d[j - 1] + 1e-7;
      if (near) expected = static_cast<int>(k);
    }
  }
  ASSERT_GE(expected, 4);
  EXPECT_NEAR(certified_at, t[expected], 0.011);
  // One mode: the bound on later returns is the last distance.
  EXPECT_DOUBLE_EQ(certificate.bound(), d.back());
  EXPECT_LE(certificate.bound({0}), d.back());
  EXPECT_TRUE(certificate.certified());
}

// The Bautin form at b1 = -0.03, b2 = 0.5: the small cycle r^2 = (b2 - sqrt(b2^2 + 4 b1)) / 2 is
// unstable, the large one (+) stable. From just outside the small one the trajectory stays
// within 1% of it for its first 8 returns, and the small cycle never certifies (not eligible);
// the large one certifies only once the trajectory has come within its radius.
TEST(ConvergenceCertificate, NeverAtAnUnstableOrbit) {
  const RadialForm system(true);
  const ParameterValues p =
      system.with_parameter(system.with_parameter(system.default_parameters(), 0, -0.03), 1, 0.5);
  const double root = std::sqrt(0.25 - 0.12);
  const double small = std::sqrt((0.5 - root) / 2), large = std::sqrt((0.5 + root) / 2);
  ConvergenceCertificate near_small(
      system, std::make_shared<OrbitNeighbourhood>(system, orbit_at(system, p, small)));
  ConvergenceCertificate near_large(
      system, std::make_shared<OrbitNeighbourhood>(system, orbit_at(system, p, large)));
  EXPECT_FALSE(near_small.eligible());
  EXPECT_GT(near_small.rate(), 1.0);
  EXPECT_TRUE(near_large.eligible());
  Flow flow(system);
  std::vector<double> times;
  for (int i = 0; i <= 40000; ++i) times.push_back(0.01 * i);
  double certified_at = -1.0, last_near_small = 0.0;
  flow.sample(Eigen::Vector2d(small * 1.0001, 0.0), p, 0.0, times,
              [&](double t, const Eigen::VectorXd& z) {
                near_small.add(t, z);
                if (std::abs(z.norm() - small) < 0.01 * small) last_near_small = t;
                if (near_large.add(t, z) && certified_at < 0) certified_at = t;
              });
  EXPECT_FALSE(near_small.certified());
  ASSERT_GE(near_small.distances().size(), 8u);
  for (int k = 0; k < 8; ++k) EXPECT_LT(near_small.distances()[k], 0.25) << k;
  ASSERT_TRUE(near_large.certified());
  EXPECT_GT(certified_at, last_near_small);
  const auto& d = near_large.distances();
  EXPECT_LT(d.back(), 0.25);
}

// A stable focus's certificate: the damped oscillator x'' + 0.2 x' + x = 0 (eigenvalues -0.1 +-
// 0.995 i) from x = 0.1 decays in its eigen-coordinates exactly as e^(-0.1 t), at the linear
// rate everywhere: certified where |c| has fallen by e since it was first inside, at t = 10 (to a
// sample of 0.01). An unstable equilibrium (the inverted pendulum-like saddle x'' = x) has no
// eligible certificate, and a run that passes it is never certified.
TEST(RestCertificate, ExactlyOneEFoldIntoAFocusAndNeverAtASaddle) {
  const testing::DampedOscillator focus(1.0, 0.2, 1.0);
  const ParameterValues p = focus.default_parameters();
  RestCertificate certificate(focus, p, Eigen::Vector2d::Zero());
  ASSERT_TRUE(certificate.eligible());
  EXPECT_NEAR(certificate.rate(), -0.1, 1e-14);
  FlowOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  Flow flow(focus, o);
  std::vector<double> times;
  for (int k = 0; k <= 2000; ++k) times.push_back(0.01 * k);
  double certified_at = -1.0;
  flow.sample_until(Eigen::Vector2d(0.1, 0.0), p, 0.0, times,
                    [&](double t, const Eigen::VectorXd& z) {
                      if (certificate.add(z) && certified_at < 0.0) certified_at = t;
                      return certified_at >= 0.0;
                    });
  EXPECT_NEAR(certified_at, 10.0, 0.0100001);

  const testing::DampedOscillator saddle(1.0, 0.0, -1.0);
  RestCertificate never(saddle, saddle.default_parameters(), Eigen::Vector2d::Zero());
  EXPECT_FALSE(never.eligible());
  for (double x : {1e-3, 1e-6, 0.0}) EXPECT_FALSE(never.add(Eigen::Vector2d(x, -x)));
}

}  // namespace
}  // namespace sympathy
