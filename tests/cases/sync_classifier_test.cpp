// The basin classifier on constructed signals whose phase differences are known exactly:
// A_i sin(2 pi f t + phi_i(t)) sampled every 0.01 s, as the basins command samples a simulation.
#include "sympathy/cases/sync_classifier.hpp"
#include "tests/support/math.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

namespace sympathy {
namespace {

using testing::kPi;
constexpr double kF = 1.733;  // Hz, the metronomes' 208 bpm

// Feeds `n` pendula x(t) = amplitude[i] * sin(2 pi f_i t + phase(i, t)) for t in [0, t_end].
SyncResult classify(std::vector<std::vector<int>> groups, SyncClassifierOptions options,
                    const std::function<double(int, double)>& phase, double t_end = 60.0,
                    std::vector<double> amplitude = {}, std::vector<double> frequency = {}) {
  int n = 0;
  for (const auto& g : groups) n += static_cast<int>(g.size());
  if (amplitude.empty()) amplitude.assign(n, 0.7);
  if (frequency.empty()) frequency.assign(n, kF);
  SyncClassifier classifier(std::move(groups), std::move(options));
  std::vector<double> angles(n);
  for (int k = 0; k * 0.01 <= t_end + 1e-9; ++k) {
    const double t = k * 0.01;
    for (int i = 0; i < n; ++i)
      angles[i] = amplitude[i] * std::sin(2 * kPi * frequency[i] * t + phase(i, t));
    classifier.add(t, angles);
  }
  return classifier.classify();
}

const std::vector<std::vector<int>> kRow{{0, 1}};
const std::vector<std::vector<int>> kCross{{0, 1}, {2, 3}};

// Constant phase leads: in-phase, anti-phase, and any other locked lead named by its value.
// Tolerance 2e-3 rad: linear interpolation of a crossing at 0.01 s and 1.733 Hz errs by at most
// about (2 pi f dt)^2 / 12 = 1e-3 rad (measured: below 1e-5 here, the errors of the two
// pendula's crossings cancelling); frequency within 1e-4 Hz (crossings 17 periods apart).
TEST(SyncClassifier, ConstantLeadsAreInPhaseAntiPhaseOrLocked) {
  const auto in = classify(kRow, {}, [](int, double) { return 0.0; });
  EXPECT_EQ(in.state, SyncState::InPhase);
  EXPECT_EQ(in.name, "in-phase");
  EXPECT_NEAR(in.phase_differences[0], 0.0, 2e-3);
  EXPECT_NEAR(in.frequency, kF, 1e-4);
  EXPECT_NEAR(in.amplitudes[1], 0.7, 1e-3);
  // In phase from the first difference measured: at pendulum 1's second crossing (t = 2 / f; its
  // crossing at t = 0 starts the signal and is not seen).
  EXPECT_NEAR(in.time_to_sync, 2.0 / kF, 0.01);

  const auto anti = classify(kRow, {}, [](int i, double) { return i * kPi; });
  EXPECT_EQ(anti.state, SyncState::AntiPhase);
  EXPECT_NEAR(std::abs(anti.phase_differences[0]), kPi, 2e-3);

  // Pendulum 2 leads by 1 rad: named by the nearest multiple of pi/16, 5 pi/16 = 0.98 rad.
  const auto locked = classify(kRow, {}, [](int i, double) { return i * 1.0; });
  EXPECT_EQ(locked.state, SyncState::Locked);
  EXPECT_EQ(locked.name, "locked+0.98");
  // 2.94 and 2.95 rad (the two ends seen on one BP-born orbit) share the name of 15 pi/16.
  for (double lead : {2.94, 2.95})
    EXPECT_EQ(classify(kRow, {}, [lead](int i, double) { return i * lead; }).name, "locked+2.95");
  EXPECT_NEAR(locked.phase_differences[0], 1.0, 2e-3);
}

// The cross setup's pairs: each pair in or anti-phase, the phase between the pairs free.
TEST(SyncClassifier, CrossSetupPairs) {
  const auto in_in = classify(kCross, {}, [](int i, double) { return i < 2 ? 0.0 : 2.0; });
  EXPECT_EQ(in_in.state, SyncState::InIn);
  const auto anti_anti = classify(kCross, {}, [](int i, double) {
    return std::vector<double>{0.0, kPi, 0.7, 0.7 + kPi}[i];
  });
  EXPECT_EQ(anti_anti.state, SyncState::AntiAnti);
  const auto in_anti = classify(kCross, {}, [](int i, double) {
    return std::vector<double>{0.0, kPi, 1.3, 1.3}[i];  // pair {1,2} anti, {3,4} in
  });
  EXPECT_EQ(in_anti.state, SyncState::InAnti);
  EXPECT_NEAR(in_anti.phase_differences[1], 1.3, 2e-3);
}

// A detuned pendulum (5% faster: 5.4 rad of drift over the 10 s window) and a modulated one
// (a quasi-periodic phase, 0.5 rad at 0.1 Hz) are not synchronized; a pendulum swinging
// below its stopped amplitude is stopped; a run shorter than the window is undetermined.
TEST(SyncClassifier, DriftModulationStopAndShortRuns) {
  const auto drift = classify(kRow, {}, [](int, double) { return 0.0; }, 60.0, {}, {kF, 1.05 * kF});
  EXPECT_EQ(drift.state, SyncState::NotSynchronized);
  EXPECT_TRUE(std::isnan(drift.time_to_sync));
  const auto quasi =
      classify(kRow, {}, [](int i, double t) { return i * 0.5 * std::sin(2 * kPi * 0.1 * t); });
  EXPECT_EQ(quasi.state, SyncState::NotSynchronized);

  SyncClassifierOptions with_stop;
  with_stop.stopped_amplitude = {0.192, 0.192};  // Table I's ths
  const auto stopped = classify(kRow, with_stop, [](int, double) { return 0.0; }, 60.0, {0.7, 0.1});
  EXPECT_EQ(stopped.state, SyncState::Stopped);
  EXPECT_NEAR(stopped.amplitudes[1], 0.1, 1e-3);

  const auto short_run = classify(
      kRow, {}, [](int, double) { return 0.0; }, 8.0);
  EXPECT_EQ(short_run.state, SyncState::Undetermined);
}

// Time to synchronize of a phase difference decaying as pi exp(-t / 5 s): it enters the 0.1 rad
// band for good at t* = 5 ln(10 pi) = 17.224 s; measured at pendulum 1's crossings, so the
// answer is the first crossing at or after t*, within one period (0.577 s) after it.
TEST(SyncClassifier, TimeToSynchronizeIsWhenThePhaseDifferenceStaysWithinItsBand) {
  const double t_star = 5.0 * std::log(10.0 * kPi);
  const auto r = classify(kRow, {}, [](int i, double t) { return i * kPi * std::exp(-t / 5.0); });
  EXPECT_EQ(r.state, SyncState::InPhase);
  EXPECT_GE(r.time_to_sync, t_star - 0.01);
  EXPECT_LE(r.time_to_sync, t_star + 1.0 / kF + 0.01);
}

TEST(SyncClassifier, OptionsNameTheField) {
  SyncClassifierOptions o;
  o.phase_tolerance = 0.0;
  ASSERT_TRUE(o.validate());
  EXPECT_EQ(o.validate()->field, "phase_tolerance");
  o = {};
  o.window = -1.0;
  EXPECT_EQ(o.validate()->field, "window");
  EXPECT_THROW(SyncClassifier({{0, 0}}, {}), std::invalid_argument);
}

}  // namespace
}  // namespace sympathy
