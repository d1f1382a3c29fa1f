// The quartiles of a sample: how a basin study summarizes the times to synchronize of the runs
// that end in one state (with the share of the state, its basin stability).
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace sympathy {

struct Quartiles {
  double q1 = std::nan(""), median = std::nan(""), q3 = std::nan("");
};

// Linear interpolation between the order statistics (position p (n - 1) for the p-quantile, as
// NumPy's and R's defaults); NaN for an empty sample. NaN values are left out.
inline Quartiles quartiles(std::vector<double> sample) {
  sample.erase(std::remove_if(sample.begin(), sample.end(), [](double x) { return std::isnan(x); }),
               sample.end());
  Quartiles q;
  if (sample.empty()) return q;
  std::sort(sample.begin(), sample.end());
  const auto at = [&](double p) {
    const double x = p * static_cast<double>(sample.size() - 1);
    const std::size_t i = static_cast<std::size_t>(std::floor(x));
    const std::size_t j = std::min(i + 1, sample.size() - 1);
    return sample[i] + (x - static_cast<double>(i)) * (sample[j] - sample[i]);
  };
  q.q1 = at(0.25);
  q.median = at(0.5);
  q.q3 = at(0.75);
  return q;
}

}  // namespace sympathy
