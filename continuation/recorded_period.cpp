#include "sympathy/continuation/recorded_period.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/recording.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

RecordedPeriod read_recorded_period(const std::string& path,
                                    const std::vector<std::string>& state_names,
                                    const std::string& system, const std::vector<int>& angles) {
  const Recording r = read_recording(path, state_names, system);
  // a - b, with the angles' differences on the circle, in (-pi, pi].
  auto difference = [&](const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
    Eigen::VectorXd d = a - b;
    for (int i : angles) d[i] = std::remainder(d[i], 2.0 * M_PI);
    return d;
  };
  const int n = static_cast<int>(state_names.size());
  // Every state, in any column order: the start is a whole state.
  std::vector<int> column(n, -1);
  for (std::size_t k = 0; k < r.components.size(); ++k)
    column[r.components[k]] = static_cast<int>(k);
  for (int i = 0; i < n; ++i)
    if (column[i] < 0)
      throw InputError(path + ":1: no column '" + state_names[i] +
                       "'; expected t and every state of " + system + " (" + join(state_names) +
                       "): the first row is the orbit's start");
  const int rows = r.samples();
  if (rows < kMinimumPeriodRows)
    throw InputError(path + ": " + std::to_string(rows) + " row" + (rows == 1 ? "" : "s") +
                     " after the header; expected at least " + std::to_string(kMinimumPeriodRows) +
                     " samples of one period (too short to be a closed orbit)");
  auto state = [&](int row) {
    Eigen::VectorXd z(n);
    for (int i = 0; i < n; ++i) z[i] = r.values(row, column[i]);
    return z;
  };

  RecordedPeriod out;
  out.path = path;
  out.rows = rows;
  out.state0 = state(0);
  out.start_time = r.times.front();
  out.span = r.times.back() - r.times.front();
  out.period = out.span;
  // The section through z0 across the motion there, its normal the first step of the data (the
  // flow's direction to first order in the sampling step): g = <n, z - z0> starts at 0, is
  // |n|^2 > 0 at the second row, and comes back up through 0 near z0 one period later. The
  // plane is crossed once more far from z0, the other way: only a crossing near z0 counts (within
  // a fifth of the farthest distance yet, as estimate_period does on a flow). An orbit of several
  // loops (a period-4 orbit of the Lorenz system) crosses near z0 once a loop: the period is the
  // first return as near z0 as the recording comes back at all (within twice the nearest
  // return's distance, or a hundredth of the farthest), not the first loop's.
  const Eigen::VectorXd normal = difference(state(1), out.state0);
  if (!(normal.cwiseAbs().maxCoeff() > 0.0))
    throw InputError(path + ":" + std::to_string(r.lines[1]) + ": the same state as line " +
                     std::to_string(r.lines[0]) +
                     "; expected samples of a periodic motion (the state moves between rows)");
  struct Return {
    double time, distance;
    int line;
  };
  std::vector<Return> returns;
  double previous_g = 0.0, farthest = 0.0, largest_step = 0.0;
  Eigen::VectorXd previous = out.state0;
  for (int row = 1; row < rows; ++row) {
    const Eigen::VectorXd z = state(row);
    largest_step = std::max(largest_step, difference(z, state(row - 1)).cwiseAbs().maxCoeff());
    const Eigen::VectorXd from_start = difference(z, out.state0);
    const double g = normal.dot(from_start);
    const double distance = from_start.cwiseAbs().maxCoeff();
    if (row > 1 && previous_g < 0.0 && g >= 0.0) {
      const double s = -previous_g / (g - previous_g);
      const Eigen::VectorXd crossing = previous + s * difference(z, previous);
      const double d = difference(crossing, out.state0).cwiseAbs().maxCoeff();
      if (d < 0.2 * farthest)
        returns.push_back(
            {r.times[row - 1] + s * (r.times[row] - r.times[row - 1]) - out.start_time, d,
             r.lines[row]});
    }
    farthest = std::max(farthest, distance);
    previous_g = g;
    previous = z;
  }
  if (!returns.empty()) {
    double nearest = returns.front().distance;
    for (const auto& x : returns) nearest = std::min(nearest, x.distance);
    const double near_enough = std::max(2.0 * nearest, 0.01 * farthest);
    const auto first = std::find_if(returns.begin(), returns.end(),
                                    [&](const Return& x) { return x.distance <= near_enough; });
    out.period = first->time;
    out.returned = true;
    out.return_line = first->line;
    return out;
  }
  // No return inside the data: it must end where it began (one period, the last row within two
  // sampling steps of the first), or it is less than a period.
  const double gap = difference(state(rows - 1), out.state0).cwiseAbs().maxCoeff();
  if (gap > 2.0 * largest_step)
    throw InputError(path + ":" + std::to_string(r.lines.back()) + ": the last row is " +
                     format_double(gap) + " from the first (line " + std::to_string(r.lines[0]) +
                     ", largest component), more than twice the largest step between rows (" +
                     format_double(largest_step) +
                     "), and the motion never comes back to the first row; expected one whole "
                     "period or more (too short?)");
  return out;
}

PeriodicOrbit orbit_from_recorded_period(const OdeSystem& system, const ParameterValues& p,
                                         const RecordedPeriod& recorded,
                                         const InvariantSubspace& subspace,
                                         const OrbitOptions& options) {
  if (!system.autonomous())
    throw std::invalid_argument(
        "orbit_from_recorded_period: for autonomous systems (a forced system's period is the "
        "forcing's: solve_periodic_orbit with it)");
  if (recorded.state0.size() != system.dimension())
    throw std::invalid_argument("orbit_from_recorded_period: a recorded state of " +
                                std::to_string(recorded.state0.size()) +
                                " values for a system of " + std::to_string(system.dimension()));
  return solve_periodic_orbit(system, p, recorded.state0, recorded.period, subspace, options);
}

}  // namespace sympathy
