// Branches of periodic orbits and the bifurcations found on them: the result of a continuation,
// which keeps what made it (the options, the system's names, the parameter values), and what the
// library does with results (joining a backward and a forward run into one branch).
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "sympathy/continuation/continuation_options.hpp"
#include "sympathy/continuation/driver.hpp"
#include "sympathy/continuation/equilibrium.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

enum class BifurcationType {
  Fold,            // LP: the branch turns back; a real multiplier passes through +1
  BranchPoint,     // BP: a real multiplier crosses +1 without a fold (symmetry-breaking pitchfork)
  PeriodDoubling,  // PD: a real multiplier crosses -1
  NeimarkSacker,   // NS: a complex pair crosses the unit circle
  // UZ: not a bifurcation but a value of the parameter asked for (ContinuationOptions::
  // user_points, AUTO's UZ): the branch's orbit there, at the value exactly, no multiplier
  // crossing.
  UserPoint,
};
std::string to_string(BifurcationType t);  // "LP", "BP", "PD", "NS", "UZ"
std::string describe(BifurcationType t);   // "fold", ...

// One computed point of a branch: a converged periodic orbit at a parameter value.
struct ContinuationPoint {
  int index = 0;  // along the branch; negative on the backward part of a two-way run
  double parameter = 0.0;
  PeriodicOrbit orbit;       // state, period, multipliers, residual, trivial-multiplier error
  Eigen::VectorXd unknowns;  // shooting unknowns (all segment states and the period)
  Eigen::VectorXd tangent;   // unit tangent (unknowns, parameter) in the scaled norm
  // The phase condition's section its unknowns satisfy, which its tangent and the next step use
  // (kept from point to point while the flow crosses it well).
  PhaseSection section;
  double step = 0.0;                // arclength step that led here (scaled)
  int iterations = 0;               // corrector iterations
  std::vector<double> description;  // what the model's OrbitDescriber says of the orbit (if any)
};

// How the location of an event ended, for programs to switch on (the note says it for people).
enum class LocationOutcome {
  Located,          // the bracket shrank to the tolerance
  NotNarrowed,      // 30 probes left the bracket wider than the tolerance
  CorrectorFailed,  // a probe of the bracket could not be corrected onto the branch
};
std::string to_string(LocationOutcome o);

// Whether an event can be trusted, and if not, why.
enum class EventTrust {
  Trusted,
  TrivialErrorTooLarge,  // a trivial-multiplier error above the trust limit near it
  NoCrossingMultiplier,  // a fold with no multiplier through +1: the branch turned back where
                         // it degenerates (an orbit shrinking into an equilibrium, a Hopf point)
  CrossingNotResolved,   // the multiplier followed across is not on the unit circle where the
                         // event was located (multipliers of 1e-17 "crossing" on long-period
                         // orbits): the computation does not resolve it
  NotCorrected,          // no orbit was corrected there: state and period interpolated between
                         // the points around it (a user point whose correction failed)
};

struct Bifurcation {
  BifurcationType type = BifurcationType::Fold;
  int multiplicity = 1;    // multipliers crossing together (2: symmetric systems do this)
  double parameter = 0.0;  // located value
  // How far the true point may lie from `parameter`: the final bracket's width plus, where a
  // multiplier crosses, the multipliers' own error (the located orbit's trivial-multiplier error)
  // over the speed at which the crossing multiplier's |mu| - 1 moves with the parameter. A slow
  // crossing is located no better than its multipliers allow, however narrow its bracket (the
  // row setup's c-branch BPs: |mu| moves by 2-5e-4 per N s/m, so a 3e-9 multiplier error moves
  // the root by about 1e-5 N s/m).
  double uncertainty = 0.0;
  double bracket = 0.0;  // width of the final bracket in the parameter
  double period = 0.0;
  FloquetAnalysis floquet;              // at the located point
  double monodromy_growth = 0.0;        // at the located point: PeriodicOrbit's
  std::complex<double> crossing = 0.0;  // the multiplier followed across (LP: nearest to +1)
  Eigen::VectorXd state0;               // orbit at the located point
  Eigen::VectorXd unknowns;
  Eigen::VectorXd tangent;
  LocationOutcome location = LocationOutcome::NotNarrowed;
  // Whether the crossing multiplier's perturbations keep or break the symmetry of the branch's
  // subspace (Unlabelled where none was declared, and for folds).
  SymmetryKind symmetry = SymmetryKind::Unlabelled;
  EventTrust trust = EventTrust::Trusted;
  std::string note;  // what to know about it (why untrusted, how it was detected), for people
  bool located() const { return location == LocationOutcome::Located; }
  bool trusted() const { return trust == EventTrust::Trusted; }
  int after_point = 0;     // index of the branch point before it
  double arclength = 0.0;  // from that point (orders events found in one interval)
  // The located orbit described (OrbitDescriber), as the branch's points are: filled by
  // continue_branch when it is given a describer; empty otherwise.
  std::vector<double> description;
  // The located orbit's samples over its period, from location's last run, for the description
  // (a plain integration of the period otherwise: 2.7% of the fast preset's anti-phase branch);
  // continue_branch empties them once described, as it does the points'.
  PeriodSamples samples;
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
  int parameter = -1;                    // its index among the system's named parameters
  std::vector<std::string> state_names;  // the system's, for writers and readers
  StepRejections rejected;
  std::vector<ContinuationPoint> points;  // in order along the branch
  std::vector<Bifurcation> events;        // in order along the branch
  StopReason stop = StopReason::ParameterBound;
  std::string stop_reason;  // the message: why, with numbers ("backward: ...; forward: ..." for
                            // a two-way branch)
  std::optional<StopReason> backward_stop;  // a two-way branch: why its backward part ended
  double seconds = 0.0;
  FlowStatistics flow;
  // Evaluations with derivatives served by the block across a symmetric orbit alone, the orbit
  // reused (ShootingProblem::use_symmetry).
  int across_evaluations = 0;
  // Evaluations with derivatives of a symmetric orbit that the parameter moves, integrated block
  // by block in one run (ShootingProblem::split_evaluations).
  int split_evaluations = 0;
  // The stiffness measured at the start where OrbitOptions::switch_when_stiff asked for it (the
  // method it chose is options.orbit.shooting.flow.method).
  std::optional<StiffnessEstimate> stiffness;
  // What made it: the options (bounds included) and the parameter values it started from.
  ContinuationOptions options;
  ParameterValues start_values;
  // Where the family ended, its orbits shrinking into an equilibrium (stop is HopfPoint): the
  // equilibrium's Hopf point, located on the equilibria (hopf.hpp).
  std::optional<HopfPoint> hopf_end;
  // Where it was born, for a switched branch ("BP at k = 47.0655622538"); empty otherwise.
  std::string origin;
  // Whether the run had a starting orbit (false: stop is StartFailed, and nothing was continued).
  bool started() const { return stop != StopReason::StartFailed; }
};

// One branch from a backward run and a forward run that started at the same orbit: the backward
// points reversed (without their copy of the start, indices negated), then the forward ones;
// events ordered along the branch. Statistics, rejections and the stop reasons are combined.
Branch join_branches(Branch backward, Branch forward);

// Sorts events along a branch: by the point before each, then by arclength from it (on the
// backward part of a joined branch, indices are negative and arclength runs the other way).
void order_events(std::vector<Bifurcation>& events);

}  // namespace sympathy
