#include "sympathy/continuation/branch.hpp"

#include <algorithm>
#include <utility>

namespace sympathy {

std::string to_string(BifurcationType t) {
  switch (t) {
    case BifurcationType::Fold:
      return "LP";
    case BifurcationType::BranchPoint:
      return "BP";
    case BifurcationType::PeriodDoubling:
      return "PD";
    case BifurcationType::NeimarkSacker:
      return "NS";
    case BifurcationType::UserPoint:
      return "UZ";
  }
  return "?";
}

std::string describe(BifurcationType t) {
  switch (t) {
    case BifurcationType::Fold:
      return "fold";
    case BifurcationType::BranchPoint:
      return "branch point";
    case BifurcationType::PeriodDoubling:
      return "period doubling";
    case BifurcationType::NeimarkSacker:
      return "Neimark-Sacker";
    case BifurcationType::UserPoint:
      return "user point";
  }
  return "?";
}

std::string to_string(StopReason r) {
  switch (r) {
    case StopReason::ParameterBound:
      return "parameter bound";
    case StopReason::PointLimit:
      return "point limit";
    case StopReason::MinimumStep:
      return "minimum step";
    case StopReason::Interrupted:
      return "interrupted";
    case StopReason::StartFailed:
      return "start failed";
    case StopReason::TurnedBack:
      return "turned back";
    case StopReason::HopfPoint:
      return "Hopf point";
  }
  return "?";
}

std::string to_string(LocationOutcome o) {
  switch (o) {
    case LocationOutcome::Located:
      return "located";
    case LocationOutcome::NotNarrowed:
      return "not narrowed";
    case LocationOutcome::CorrectorFailed:
      return "corrector failed";
  }
  return "?";
}

void order_events(std::vector<Bifurcation>& events) {
  std::stable_sort(events.begin(), events.end(), [](const auto& a, const auto& b) {
    if (a.after_point != b.after_point) return a.after_point < b.after_point;
    return a.after_point < 0 ? a.arclength > b.arclength : a.arclength < b.arclength;
  });
}

Branch join_branches(Branch backward, Branch forward) {
  Branch joined;
  joined.parameter_name = forward.parameter_name;
  joined.parameter = forward.parameter;
  joined.state_names = forward.state_names;
  joined.options = forward.options;
  joined.start_values = forward.start_values;
  joined.stiffness = backward.stiffness ? backward.stiffness : forward.stiffness;
  for (auto& p : backward.points) p.index = -p.index;
  // The point before each event along the joined branch: -(k+1) for one between -k and -(k+1).
  for (auto& e : backward.events) e.after_point = -(e.after_point + 1);
  if (!backward.points.empty())
    for (auto it = backward.points.rbegin(); it != backward.points.rend() - 1; ++it)
      joined.points.push_back(std::move(*it));
  for (auto& p : forward.points) joined.points.push_back(std::move(p));
  for (auto& e : backward.events) joined.events.push_back(std::move(e));
  for (auto& e : forward.events) joined.events.push_back(std::move(e));
  order_events(joined.events);
  joined.stop = forward.stop;
  joined.backward_stop = backward.stop;
  joined.stop_reason = "backward: " + backward.stop_reason + "; forward: " + forward.stop_reason;
  joined.rejected = backward.rejected;
  joined.rejected += forward.rejected;
  joined.flow = backward.flow;
  joined.flow += forward.flow;
  joined.across_evaluations = backward.across_evaluations + forward.across_evaluations;
  joined.split_evaluations = backward.split_evaluations + forward.split_evaluations;
  joined.seconds = backward.seconds + forward.seconds;
  return joined;
}

}  // namespace sympathy
