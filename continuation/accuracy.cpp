#include "sympathy/continuation/accuracy.hpp"

namespace sympathy {

std::string to_string(Accuracy accuracy) {
  switch (accuracy) {
    case Accuracy::Fast:
      return "fast";
    case Accuracy::Default:
      return "default";
    case Accuracy::High:
      return "high";
  }
  return "default";
}

std::optional<Accuracy> accuracy_named(std::string_view name) {
  for (Accuracy a : {Accuracy::Fast, Accuracy::Default, Accuracy::High})
    if (name == to_string(a)) return a;
  return std::nullopt;
}

namespace {

// The transient's integrator: it only has to approach the orbit (its checks ask for 2e-3 of the
// state's size), so BDF, stiff-safe, at rtol 1e-8.
FlowOptions library_transient() {
  FlowOptions f;
  f.rtol = 1e-8;
  f.atol = 1e-10;
  return f;
}

}  // namespace

// Chosen by measurement on `sympathy continue cases/row2.toml --start anti-phase --param k --from 1
// --to 100` (2026-11-23, 2-core machine shared with another build, single runs; bench section (f)
// repeats them). Error: the largest relative error of the located BP, NS, NS against BDF at rtol
// 1e-13; trivial: the largest |mu - 1| over the branch's points.
//
//   integrator (shooting flow)          rtol    error    trivial  seconds  steps
//   forward module, BDF (before)        1e-11   8.7e-10  7.3e-09  3.70     700,441
//   forward module, BDF                 1e-12   5.1e-10  1.2e-09  5.01     874,988
//   forward module, Adams               1e-11   6.5e-10  7.7e-09  2.33     323,901
//   augmented, BDF (dense Newton)       1e-11   8.9e-10  1.1e-08  4.81     654,205
//   augmented, Adams                    1e-11   7.0e-10  1.1e-08  1.87     311,194
//   augmented, Adams  (default)         5e-12   6.5e-10  5.6e-09  2.03     319,770
//   augmented, Adams  (high)            1e-12   5.2e-10  8.4e-10  2.40     349,807
//   ERK Dormand-Prince                  1e-10   5.2e-10  4.2e-10  1.23     197,641
//   ERK Dormand-Prince, ERK transient (fast) 1e-8  2.2e-09  1.0e-07  0.72   93,006
//   ERK Dormand-Prince, ERK transient   1e-7    5.9e-08  5.0e-06  0.67     80,333
//   ERK Dormand-Prince, ERK transient   5e-7    4.4e-07  2.1e-05  0.65     76,756
//
// Default: the fastest CVODE configuration with the located points within 1e-8 and every trivial
// multiplier within 1e-8 of 1 (augmented Adams at 1e-11 misses the latter by a hair). Below ~5e-10
// the corrector's and location's tolerances, not the integration, set the error. Adams with
// fixed-point iteration is not stiff-safe: a stiff platform (large k, c) wants --method bdf.
// Fast: Dormand-Prince's steps here are set by the turning-point caps, not by the tolerance
// (93,006 steps at 1e-8, 76,756 at 5e-7), so loosening rtol from 1e-8 to 5e-7 buys 10% for 200x the
// error, and from 2e-8 up some points' trivial error passes the trust limit (1e-6; 9.4e-6 at 2e-8)
// and events get reported as not trusted; hence 1e-8 (`--accuracy fast --rtol 5e-7` gives the
// 4e-7 of AUTO's best setting). Its transient (60 s before the first Newton) is Dormand-Prince
// too: 0.72 s against 0.83 s with the BDF transient.
// After each point's scales and description came from its own shooting run and the corrector
// started with the run with sensitivities where predictions land (2026-11-24, bench section (f),
// CPU seconds, the machine's load average about 5): fast 2.9e-9 in 0.43 s, default 1.1e-10 in
// 1.39 s, high 3.3e-11 in 1.62 s; the choice above stands.
// After the one-evaluation right-hand side (2026-11-24, bench section (f), CPU seconds): fast
// 1.5e-9 in 0.26 s, default 9.9e-11 in 0.73 s, high 3.9e-11 in 0.84 s. Dormand-Prince alone at
// rtol 1e-7 (a BDF transient) gave 1.4e-7 in 0.21 s, within AUTO's best but 30 times fast's
// error; the choice above stands.
void apply_accuracy(Accuracy accuracy, OrbitOptions& o) {
  FlowOptions& f = o.shooting.flow;
  // Every preset's integrator is a non-stiff one: BDF where the start measures stiff for it.
  o.switch_when_stiff = true;
  switch (accuracy) {
    case Accuracy::Fast:
      f.method = Method::ERK;
      f.sensitivities = Sensitivities::Augmented;
      f.explicit_table = ExplicitTable::DormandPrince;
      f.rtol = 1e-8;
      f.atol = 1e-10;
      // The transient too: plain Dormand-Prince on the state at the transient's own tolerance.
      o.transient_flow.method = Method::ERK;
      o.transient_flow.sensitivities = Sensitivities::Augmented;
      // The transient only has to approach the orbit (its checks ask for 2e-3 of the state's
      // size; Newton's rough iterations, at this tolerance too, get the orbit to about 1e-7, and
      // the polish at the shooting's rtol takes one iteration from there either way): at rtol
      // 1e-6 instead of 1e-8 the anti-phase start takes 4 799 steps instead of 6 671, the
      // anti-phase k-branch 22 025 instead of 24 415 (its located points as close to the
      // reference), the in-phase one 49 975 instead of 52 832.
      o.transient_flow.rtol = 1e-6;
      o.transient_flow.atol = 1e-8;
      // Dormand-Prince's steps here are the turning-point caps' (above): each a larger share of
      // the band it crosses, still below the 2/3 that would let a step jump a level (Flow): fast
      // 0.22 -> 0.21 CPU s (medians of five), 47 875 -> 43 730 steps, the events within 1e-8.
      f.steep_step_fraction = 0.6;
      o.transient_flow.steep_step_fraction = 0.6;
      break;
    case Accuracy::Default:
    case Accuracy::High:
      // The same integrator, the high preset five times tighter; the transient and the
      // turning-point caps the library's (BDF at rtol 1e-8, FlowOptions' caps), whatever preset
      // the options had before.
      o.transient_flow = library_transient();
      f.steep_step_fraction = FlowOptions{}.steep_step_fraction;
      f.explicit_table = ExplicitTable::DormandPrince;
      f.method = Method::Adams;
      f.nonlinear_solver = NonlinearSolver::FixedPoint;
      f.sensitivities = Sensitivities::Augmented;
      f.rtol = accuracy == Accuracy::High ? 1e-12 : 5e-12;
      f.atol = 1e-2 * f.rtol;
      break;
  }
}

// Fast's steps (2026-11-24, the same branch, single runs of `continue --accuracy fast`): the
// multipliers' motion near the unit circle set most of the 65 points (47 of them between k = 45
// and 58) and the range's 25th the rest. Letting a multiplier's modulus move 0.05 a step instead
// of 0.02 and the parameter a tenth of the range: 44 points, the same three events, each moved
// by at most 1.5e-9 relative (the location, not the integration, sets that). Neither setting sees
// a multiplier that leaves the unit circle and comes back within one step; the looser one lets
// such an excursion be larger (0.05 in modulus instead of 0.02): crossings that close together
// are what the default preset is for.
void apply_accuracy(Accuracy accuracy, ContinuationOptions& o) {
  apply_accuracy(accuracy, o.orbit);
  const ContinuationOptions library;
  o.max_modulus_change = accuracy == Accuracy::Fast ? 0.05 : library.max_modulus_change;
  o.parameter_steps = accuracy == Accuracy::Fast ? 10.0 : library.parameter_steps;
}

}  // namespace sympathy
