// Branches of periodic orbits and the bifurcations found on them.
#pragma once

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

enum class BifurcationType {
  Fold,            // LP: the branch turns back; a real multiplier passes through +1
  BranchPoint,     // BP: a real multiplier crosses +1 without a fold (symmetry-breaking pitchfork)
  PeriodDoubling,  // PD: a real multiplier crosses -1
  NeimarkSacker,   // NS: a complex pair crosses the unit circle
};
std::string to_string(BifurcationType t);  // "LP", "BP", "PD", "NS"
std::string describe(BifurcationType t);   // "fold", ...

// One computed point of a branch: a converged periodic orbit at a parameter value.
struct ContinuationPoint {
  int index = 0;  // along the branch; negative on the backward part of a two-way run
  double parameter = 0.0;
  PeriodicOrbit orbit;             // state, period, multipliers, residual, trivial-multiplier error
  Eigen::VectorXd unknowns;        // shooting unknowns (all segment states and the period)
  Eigen::VectorXd tangent;         // unit tangent (unknowns, parameter) in the scaled norm
  Eigen::VectorXd section;         // point the phase section goes through, for the tangent and the
                                   // next step (kept while the flow crosses it well)
  Eigen::VectorXd section_normal;  // its normal
  double step = 0.0;               // arclength step that led here (scaled)
  int iterations = 0;              // corrector iterations
};

struct Bifurcation {
  BifurcationType type = BifurcationType::Fold;
  int multiplicity = 1;      // multipliers crossing together (2: symmetric systems do this)
  double parameter = 0.0;    // located value
  double uncertainty = 0.0;  // width of the final bracket in the parameter
  double period = 0.0;
  FloquetAnalysis floquet;              // at the located point
  std::complex<double> crossing = 0.0;  // the multiplier followed across (LP: nearest to +1)
  Eigen::VectorXd state0;               // orbit at the located point
  Eigen::VectorXd unknowns;
  Eigen::VectorXd tangent;
  bool located = false;    // the bracket shrank to the tolerance
  bool trusted = true;     // false: a trivial-multiplier error too large near it
  std::string note;        // what to know about it (why untrusted, how it was detected)
  int after_point = 0;     // index of the branch point before it
  double arclength = 0.0;  // from that point (orders events found in one interval)
};

// Steps rejected and retried shorter, by reason: what step control did on a branch.
struct StepRejections {
  int corrector = 0;    // the corrector failed
  int turn = 0;         // the tangent turned too far
  int multipliers = 0;  // multipliers near the circle moved too far, or ambiguously
  int location = 0;     // a bifurcation in the step could not be located
  StepRejections& operator+=(const StepRejections& o) {
    corrector += o.corrector;
    turn += o.turn;
    multipliers += o.multipliers;
    location += o.location;
    return *this;
  }
};

struct Branch {
  std::string parameter_name;
  StepRejections rejected;
  std::vector<ContinuationPoint> points;
  std::vector<Bifurcation> events;
  std::string stop_reason;
  double seconds = 0.0;
  FlowStatistics flow;
};

}  // namespace sympathy
