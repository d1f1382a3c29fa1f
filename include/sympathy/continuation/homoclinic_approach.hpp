// Where a family of periodic orbits approaches a homoclinic orbit: its period grows without bound
// while the parameter converges (as |p - p_h| ~ exp(-lambda T) at a saddle, oscillating about p_h
// with a decaying amplitude at a saddle-focus, where folds come every 2 pi / omega of period).
// Continued on, its orbits spend ever longer near the equilibrium and their monodromies grow as
// exp(lambda T): on AUTO's pp2 the trivial multiplier's error passes 1e-3 at T 94 and 100 at T
// 150, at a quota that no longer changes in 9 digits. The branch ends there.
#pragma once

#include <optional>
#include <vector>

namespace sympathy {

// What the approach is recognised from: each accepted point's, in order along the branch.
struct PeriodRecord {
  double parameter = 0.0, period = 0.0;
  double trivial_error = 0.0;  // the trivial multiplier's error (FloquetAnalysis)
};

struct HomoclinicApproach {
  double parameter = 0.0;         // the last point's
  double from_period = 0.0;       // the least period on the stretch
  double to_period = 0.0;         // the last point's
  double parameter_spread = 0.0;  // the stretch's largest |p - p_last|
};

// The approach is recognised when, over the trailing stretch of points whose parameters lie within
// `tolerance` of the last one's, the period has at least doubled and is still growing at the last
// point. (A canard explosion also grows the period at a nearly fixed parameter, but by a bounded
// factor: 1.56 on AUTO's fhn within 1e-4 of a = 0.4305, 6.5 to 16.2 in all.)
std::optional<HomoclinicApproach> homoclinic_approach(const std::vector<PeriodRecord>& history,
                                                      double tolerance);

// A slower approach, seen through its orbits: trivial-multiplier errors above kUnresolved on every
// point of a trailing stretch over which the period grew by kGrowth, and still growing. Near a
// homoclinic orbit the monodromy grows as exp(lambda T) and its multipliers are lost first (AUTO's
// pen, its PD branch: errors above 1e-2 from T 42 on, the parameter still moving 5e-3 relative
// while T doubles, 565 points in 52 s up to errors of 3e7); strongly unstable orbits that a family
// passes through have such errors too, but their period does not keep growing (AUTO's ab at p2 =
// 16: errors of 4 to 62 while T grows 13% and falls again). `parameter_spread` is then the
// stretch's.
constexpr double kUnresolved = 1e-2, kGrowth = 1.25;
std::optional<HomoclinicApproach> unresolved_approach(const std::vector<PeriodRecord>& history);

}  // namespace sympathy
