#include "sympathy/continuation/location.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "sympathy/continuation/crossing_locator.hpp"
#include "sympathy/continuation/multiplier_tracking.hpp"

namespace sympathy {

Bifurcation locate(const ContinuationPoint& a, const ContinuationPoint& b, BifurcationType type,
                   int multiplicity, std::complex<double> mu_a, std::complex<double> mu_b,
                   double tolerance, double scale_floor, const PointAt& point_at,
                   bool beside_fold) {
  const int N = static_cast<int>(a.unknowns.size());  // the parameter's entry of the tangents
  const double sb = b.step;
  // The multiplier followed across, by continuity: the one nearest the value interpolated
  // between the multipliers followed at the current ends of the bracket (for a fold, the
  // nontrivial one nearest to 1).
  auto tracked = [&](const ContinuationPoint& p, double s, const auto& lo, const auto& hi) {
    const std::complex<double> expected =
        type == BifurcationType::Fold
            ? 1.0
            : lo.sample.tag + (s - lo.s) / (hi.s - lo.s) * (hi.sample.tag - lo.sample.tag);
    std::complex<double> found = 0.0;
    double best = std::numeric_limits<double>::infinity();
    for (const auto& m : nontrivial(p.orbit.floquet))
      if (std::abs(m.value - expected) < best) {
        best = std::abs(m.value - expected);
        found = m.value;
      }
    return found;
  };
  // The test function: the tangent's parameter component for a fold; |mu| - 1 of the
  // multiplier followed otherwise.
  const double turn_a = a.tangent[N];
  auto test = [&](const ContinuationPoint& p, std::complex<double> mu) {
    if (type == BifurcationType::Fold) return p.tangent[N];
    const double across = std::abs(mu) - 1.0;
    return beside_fold && p.tangent[N] * turn_a < 0.0 ? -across : across;
  };
  Bifurcation e;
  e.type = type;
  e.multiplicity = multiplicity;
  using Ends = driver::End<std::complex<double>>;
  const auto sample = [&](const ContinuationPoint& p, double s, const Ends& lo, const Ends& hi) {
    const std::complex<double> mu = tracked(p, s, lo, hi);
    return driver::Sample<std::complex<double>>{test(p, mu), mu};
  };
  driver::LocatorOptions o;
  o.tolerance = tolerance;
  o.floor = scale_floor;
  o.fold = type == BifurcationType::Fold;
  // A probe whose corrector fails is tried beside it (1e-3 of the bracket each way): at a fold
  // the parameter is flat, so a location stopped there is exact in the parameter but not along
  // the branch (tor's fold at T 39.37 stopped 6.7e-6 off in the period on a corrector that
  // diverged at residual 3.9e-8).
  o.probe_beside = true;
  auto located = driver::locate_crossing(
      a, driver::Sample<std::complex<double>>{test(a, mu_a), mu_a}, b,
      driver::Sample<std::complex<double>>{test(b, mu_b), mu_b}, sb, sample, point_at,
      [](const ContinuationPoint& p) { return p.parameter; }, o);
  ContinuationPoint best = std::move(located.point);
  const std::complex<double> mu_best = located.sample.tag;
  e.location = located.outcome == driver::LocatorOutcome::Located ? LocationOutcome::Located
               : located.outcome == driver::LocatorOutcome::ProbeFailed
                   ? LocationOutcome::CorrectorFailed
                   : LocationOutcome::NotNarrowed;
  if (located.outcome == driver::LocatorOutcome::ProbeFailed)
    e.note = "location stopped: " + located.why;
  const double s_best = located.s;
  e.parameter = best.parameter;
  e.arclength = s_best;
  e.bracket = located.bracket;
  e.uncertainty = e.bracket;
  if (type != BifurcationType::Fold) {
    // The crossing speed over the whole step (a to b), which rounding does not blur as it
    // would a final bracket of 1e-8 relative width.
    const double dp = std::abs(b.parameter - a.parameter);
    const double speed = dp > 0.0 ? std::abs(test(b, mu_b) - test(a, mu_a)) / dp : 0.0;
    const double error = best.orbit.floquet.trivial_error;
    if (speed > 0.0) e.uncertainty += error / speed;
  }
  e.period = best.orbit.period;
  e.floquet = best.orbit.floquet;
  e.monodromy_growth = best.orbit.monodromy_growth;
  const driver::End<std::complex<double>> none;
  e.crossing = type == BifurcationType::Fold ? tracked(best, 0.0, none, none) : mu_best;
  if (type != BifurcationType::Fold) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& m : nontrivial(best.orbit.floquet))
      if (std::abs(m.value - e.crossing) < nearest) {
        nearest = std::abs(m.value - e.crossing);
        e.symmetry = m.symmetry;
      }
  }
  if (e.crossing.imag() < 0.0) e.crossing = std::conj(e.crossing);
  // A step may see a real multiplier on one side of the circle and, on the other, one of a
  // complex pair it has joined since (the anti-phase k-branch's breaking multiplier crosses +1 at
  // k = 47.066 and meets another real one at 47.1): what crosses is what the located point has.
  if (e.location == LocationOutcome::Located && type != BifurcationType::Fold) {
    const bool real = is_real(e.crossing);
    const BifurcationType crossed = !real                     ? BifurcationType::NeimarkSacker
                                    : e.crossing.real() > 0.0 ? BifurcationType::BranchPoint
                                                              : BifurcationType::PeriodDoubling;
    if (crossed != type) {
      e.note = std::string("the multiplier followed is ") + (real ? "real" : "complex") +
               " where it crosses, " + (real ? "complex" : "real") +
               " at an end of the step that found it";
      e.type = crossed;
    }
  }
  e.state0 = best.orbit.state0;
  e.unknowns = best.unknowns;
  e.tangent = best.tangent;
  e.samples = std::move(best.orbit.samples);
  if (e.location == LocationOutcome::NotNarrowed) e.note = "location did not reach the tolerance";
  return e;
}

}  // namespace sympathy
