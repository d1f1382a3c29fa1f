// A share of runs and its confidence interval: how often a state won, out of n random starts.
//
// The Wilson score interval (E. B. Wilson, J. Am. Stat. Assoc. 22, 209-212, 1927), not the
// normal-approximation ("Wald") interval p +- z sqrt(p (1 - p) / n): Wald collapses to the single
// point 0 or 1 when every run ends in one state (0 of 100 is not "certainly never"), and it
// leaves [0, 1] for small counts; Wilson's interval stays inside [0, 1] and keeps its coverage
// near the nominal 95% down to a few dozen runs (Newcombe, Stat. Med. 17, 857-872, 1998, method 3
// of seven compared there; his example: 81 of 263 gives 0.2553 to 0.3662).
#pragma once

#include <cstddef>

namespace sympathy {

struct Proportion {
  std::size_t count = 0;   // runs in the state
  std::size_t trials = 0;  // runs in all
  double share = 0.0;      // count / trials (0 when trials is 0)
  double lower = 0.0;      // the confidence interval's ends, inside [0, 1]
  double upper = 1.0;
};

// z of the two-sided 95% interval: the standard normal's 97.5% quantile.
inline constexpr double kZ95 = 1.959963984540054;

// The Wilson score interval of count out of trials at quantile z (trials 0: the whole [0, 1]).
// Throws std::invalid_argument if count > trials or z is not positive.
Proportion wilson_interval(std::size_t count, std::size_t trials, double z = kZ95);

}  // namespace sympathy
