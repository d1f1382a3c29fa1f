// Orbits of the row setup far from the paper's tables: a near-discontinuous escapement, no and
// heavy platform damping, a nearly rigid, a nearly massless and a nearly immovable platform.
// Every one must converge at default settings with its accuracy figures; without hinge damping
// nothing balances the escapement's drive and the failure must say so.
#include <gtest/gtest.h>

#include <algorithm>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {
namespace {

struct Extreme {
  std::string start, key;
  double value;
};

void PrintTo(const Extreme& e, std::ostream* os) {
  *os << e.start << " " << e.key << "=" << e.value;
}

PeriodicOrbit row_orbit(const std::string& start, const std::vector<Assignment>& sets) {
  const auto file = CaseFile::load(std::string(SYMPATHY_SOURCE_DIR) + "/cases/row2.toml");
  const MetronomeModel model(file.spec("table2", sets));
  const auto& s = file.start(start);
  return find_periodic_orbit(model, model.default_parameters(), file.initial_state(&s),
                             file.invariant_subspace(s, model), OrbitOptions{});
}

class ExtremeParameters : public ::testing::TestWithParam<Extreme> {};

TEST_P(ExtremeParameters, OrbitConvergesWithItsAccuracy) {
  const auto& e = GetParam();
  const PeriodicOrbit orbit = row_orbit(e.start, {{e.key, e.value, "test"}});
  ASSERT_TRUE(orbit.converged()) << orbit.newton.reason;
  EXPECT_LT(orbit.residual, 1e-9);
  EXPECT_LT(orbit.floquet.trivial_error, 1e-8);
  // Anti-phase, the platform stays at rest (MODEL.md), so M, c and k cannot change the orbit:
  // its period is Table II's, 0.5814490514 s (computed at rtol 1e-13 by `sympathy bench`).
  if (e.start == "anti-phase" && e.key != "eps") {
    EXPECT_NEAR(orbit.period, 0.5814490514, 1e-8);
  }
}

INSTANTIATE_TEST_SUITE_P(
    Row2, ExtremeParameters,
    ::testing::Values(Extreme{"in-phase", "eps", 0.005}, Extreme{"anti-phase", "eps", 0.005},
                      Extreme{"in-phase", "c", 0.0}, Extreme{"anti-phase", "c", 0.0},
                      Extreme{"in-phase", "c", 50.0}, Extreme{"anti-phase", "c", 50.0},
                      Extreme{"in-phase", "k", 1e4}, Extreme{"anti-phase", "k", 1e4},
                      Extreme{"in-phase", "M", 1e-3}, Extreme{"anti-phase", "M", 1e-3},
                      Extreme{"in-phase", "M", 100.0}, Extreme{"anti-phase", "M", 100.0}),
    [](const auto& info) {
      std::string s = info.param.start + "_" + info.param.key + "_" +
                      std::to_string(static_cast<int>(info.index));
      std::replace(s.begin(), s.end(), '-', '_');
      return s;
    });

// d = 0: the escapement feeds energy each swing and the hinges take none out, so the swing
// grows (a 600 s simulation: th1 reaches 2.5 rad by 60 s, then the pendula go over the top) and
// there is no periodic orbit. Newton must fail and say why.
TEST(ExtremeParameters, NoHingeDampingFailsWithADiagnosis) {
  for (const std::string start : {"in-phase", "anti-phase"}) {
    const PeriodicOrbit orbit = row_orbit(start, {{"d", 0.0, "test"}});
    EXPECT_FALSE(orbit.converged()) << start;
    EXPECT_NE(orbit.newton.reason.find("had not settled on a periodic orbit"), std::string::npos)
        << orbit.newton.reason;
  }
}

}  // namespace
}  // namespace sympathy
