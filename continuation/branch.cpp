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
  joined.hopf_end = forward.hopf_end ? forward.hopf_end : backward.hopf_end;
  joined.origin = forward.origin.empty() ? backward.origin : forward.origin;
  // The driver's join: the backward part reversed (indices negated, tangents along the joined
  // branch, each event after the point before it), the start once, the forward part.
  driver::Result<ContinuationPoint, Bifurcation> back, ahead;
  back.points = std::move(backward.points);
  back.events = std::move(backward.events);
  back.stop = backward.stop;
  back.message = std::move(backward.stop_reason);
  ahead.points = std::move(forward.points);
  ahead.events = std::move(forward.events);
  ahead.stop = forward.stop;
  ahead.message = std::move(forward.stop_reason);
  auto r = driver::join(std::move(back), std::move(ahead));
  joined.points = std::move(r.points);
  joined.events = std::move(r.events);
  order_events(joined.events);
  joined.stop = r.stop;
  joined.backward_stop = r.backward_stop;
  joined.stop_reason = std::move(r.message);
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
