// The paper's simulation findings (Sec. III and IV, Figs. 3, 5, 10, 11, 15, 17), reproduced by
// integrating the model and reading phases off upward zero crossings.
#include <gtest/gtest.h>

#include <numbers>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/core/flow.hpp"
#include "sympathy/core/oscillation.hpp"
#include "tests/support/math.hpp"

namespace sympathy {
namespace {

using testing::kPi;

struct SimulationRun {
  OscillationSummary end;  // over the last 10 s
  Eigen::VectorXd state;   // final state
};

// Simulates `name` from the given angles (rest otherwise) and summarizes the last 10 s.
SimulationRun simulate(const std::string& name, const std::string& params,
                       const std::vector<double>& angles, double t_end,
                       Escapement escapement = Escapement::Half) {
  const auto file = CaseFile::load(std::string(SYMPATHY_SOURCE_DIR) + "/cases/" + name + ".toml");
  ModelSpec spec = file.spec(params);
  spec.escapement = escapement;
  MetronomeModel model(spec);
  FlowOptions o;
  o.rtol = 1e-8;
  o.atol = 1e-10;
  Flow flow(model, o);
  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(model.dimension());
  std::vector<int> phases, watched;
  for (int i = 0; i < model.metronome_count(); ++i) {
    z0[model.angle_index(i)] = angles[i];
    phases.push_back(model.angle_index(i));
  }
  for (int a = 0; a < model.platform_directions(); ++a) watched.push_back(a);
  watched.insert(watched.end(), phases.begin(), phases.end());
  OscillationAnalyzer analyzer(phases, watched, 10.0);
  std::vector<double> times;
  for (int k = 0; k <= static_cast<int>(t_end * 200); ++k) times.push_back(k / 200.0);
  SimulationRun run;
  flow.sample(z0, model.default_parameters(), 0.0, times, [&](double t, const Eigen::VectorXd& z) {
    analyzer.add(t, z);
    run.state = z;
  });
  run.end = analyzer.summary();
  return run;
}

// Distance of a phase from a target on the circle.
double phase_distance(double phase, double target) {
  return std::abs(std::remainder(phase - target, 2 * kPi));
}

// Table II, started at th1 = 0.3, th2 = -0.25: the pendula end in phase (Figs. 3, 5). The
// approach is a slow damped swing of the phase difference, so give it 200 s.
TEST(PaperSimulations, RowTable2EndsInPhase) {
  const SimulationRun run = simulate("row2", "table2", {0.3, -0.25}, 200.0);
  EXPECT_LT(phase_distance(run.end.phase_differences[0], 0.0), 0.05);
  EXPECT_NEAR(run.end.frequency, 104.0 / 60.0, 0.01);  // 208 bpm: 104 cycles a minute
  EXPECT_NEAR(run.end.amplitudes[1], run.end.amplitudes[2], 1e-3);
  EXPECT_GT(run.end.amplitudes[0], 1e-4);  // the platform moves (m)
}

// The same with the discontinuous escapement (eq. 2), integrated with restarts at its
// switching surfaces: the same outcome.
TEST(PaperSimulations, RowTable2ImpulsiveEscapementEndsInPhase) {
  const SimulationRun run = simulate("row2", "table2", {0.3, -0.25}, 200.0, Escapement::Impulsive);
  EXPECT_LT(phase_distance(run.end.phase_differences[0], 0.0), 0.05);
}

// Table III (stiffer cables): in- and anti-phase both attract (Figs. 10, 11).
TEST(PaperSimulations, RowTable3BothSynchronizedStatesAttract) {
  const SimulationRun anti = simulate("row2", "table3", {0.3, -0.25}, 200.0);
  EXPECT_LT(phase_distance(anti.end.phase_differences[0], kPi), 0.05);
  EXPECT_LT(anti.end.amplitudes[0], 1e-6);  // the platform comes to rest (m)
  const SimulationRun in = simulate("row2", "table3", {0.3, 0.25}, 200.0);
  EXPECT_LT(phase_distance(in.end.phase_differences[0], 0.0), 0.05);
  EXPECT_GT(in.end.amplitudes[0], 1e-4);
}

// Table IV, cross: each diagonal pair locks in phase within about 20 s; the phase difference
// between the pairs stays wherever it lands (Figs. 15, 17): it is the same at 100 s and 200 s.
TEST(PaperSimulations, CrossPairsLockAndTheirPhaseDifferenceFreezes) {
  const std::vector<double> start{0.3, 0.2, -0.1, 0.25};
  const SimulationRun early = simulate("cross4", "table4", start, 100.0);
  const SimulationRun late = simulate("cross4", "table4", start, 200.0);
  const auto& d = late.end.phase_differences;         // th2, th3, th4 relative to th1
  EXPECT_LT(phase_distance(d[0], 0.0), 0.05);         // pair {1,2} in phase
  EXPECT_LT(phase_distance(d[2] - d[1], 0.0), 0.05);  // pair {3,4} in phase
  EXPECT_GT(phase_distance(d[1], 0.0), 0.5);          // the pairs did not lock to each other
  EXPECT_LT(phase_distance(d[1], early.end.phase_differences[1]), 0.02);
}

}  // namespace
}  // namespace sympathy
