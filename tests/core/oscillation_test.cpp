#include "sympathy/core/oscillation.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace sympathy {
namespace {

// Exact sinusoids: frequency, amplitudes and a known phase lead are recovered.
TEST(OscillationAnalyzer, RecoversFrequencyAmplitudeAndPhase) {
  const double f = 1.7, lead = 0.9, pi = std::numbers::pi;
  OscillationAnalyzer analyzer({0, 1}, {0, 1}, 5.0);
  Eigen::VectorXd z(2);
  for (int k = 0; k <= 20000; ++k) {
    const double t = k * 1e-3;
    z << 0.5 * std::sin(2 * pi * f * t), 0.2 * std::sin(2 * pi * f * t + lead);
    analyzer.add(t, z);
  }
  const auto s = analyzer.summary();
  EXPECT_NEAR(s.frequency, f, 1e-6);
  EXPECT_NEAR(s.amplitudes[0], 0.5, 1e-4);
  EXPECT_NEAR(s.amplitudes[1], 0.2, 1e-4);
  // Linear interpolation of crossings at 1 ms sampling: error ~ (2 pi f dt)^2 / 12 rad.
  EXPECT_NEAR(s.phase_differences[0], lead, 1e-5);
  EXPECT_GE(s.cycles, 8);
}

}  // namespace
}  // namespace sympathy
