// The periodic-orbit problem by single or multiple shooting.
//
// Unknowns x = [z_0, ..., z_{m-1}, T] for an autonomous system; the period is fixed (and not an
// unknown) for a periodically forced one. Residual
//   r_j = Phi(z_j over T/m) - z_{j+1}   (j = 0..m-1, z_m = z_0),
//   r_p = <n, z_0 - z_ref>              (phase condition, autonomous only: a Poincare section
//                                       through a reference point, across the flow there:
//                                       n = f(z_ref), or f(z_ref) in a chosen metric).
// States declared as angles (OdeSystem::angle_states) may gain 2 pi k over the period (a
// rotating pendulum): the wrap-around residual is then Phi(z_{m-1}) - (z_0 + 2 pi k), with the
// whole numbers k per angle (the winding) taken from the guess (unknowns_from) and fixed while
// Newton and continuation run; the Jacobian is unchanged.
// The Jacobian is block sparse: the segments' transition matrices on the block diagonal, -I on
// the block superdiagonal (cyclically), f at the segment ends / m in the period column, n in the
// phase row. Derivatives come from the flow's forward sensitivities.
//
// A residual without derivatives comes from a plain integration at rtol / 100 and atol / 10: a
// run with sensitivities keeps them in its error test, which shrinks its steps, so at equal
// settings its state is about 50 times more accurate than a plain run's (about 1e-10 against
// 5e-9 after one period at rtol 1e-11). Tightened, the plain run agrees with it to about 1e-10
// at about a tenth of its cost, and Newton-like steps on plain residuals can finish a point that
// a run with sensitivities then accepts.
//
// Symmetric orbits whose symmetric motion the parameter leaves alone (use_symmetry). An orbit in
// the fixed space V of a reflection g that f keeps (InvariantSubspace::reflection; the row
// setup's anti-phase orbit: x = 0, th2 = -th1) has a monodromy that is block diagonal in V and
// its complement W (core/across_variations.hpp). Where, moreover, the field restricted to V does
// not depend on the continued parameter along the orbit (the anti-phase orbit's platform stands
// still: k, c and M act only across V), the orbit and V's block are the same at every parameter
// value and only W's block changes. An evaluation with derivatives then reuses the last full one
// (its orbit, V's block, residual and samples) and integrates only the orbit in V with W's block
// (2 + 4 x 4 entries instead of 6 + 7 x 6 on the row setup), provided, at the new parameter values
// and each time:
//   - the unknowns are within 1e-10 (relative) of the remembered ones (the residual and the
//     Jacobian are then the remembered ones updated to first order in the difference);
//   - f keeps the reflection (equivariance_defect below 1e-12);
//   - at every 20th of the orbit's 801 samples, the restricted field's derivative in the
//     parameter is exactly zero, and the restricted field and its Jacobian on V are bit for bit
//     the remembered ones;
//   - the orbit integrated with W's block closes on itself as the remembered one did (within
//     1e-7 of its scale).
// Symmetric orbits that the parameter moves (the in-phase orbit: th2 = th1, the platform moving
// with k). With augmented sensitivities (FlowOptions::sensitivities; the forward-sensitivity
// module stays the whole computation, the cross-check), an evaluation with derivatives of a point
// in V integrates the orbit in V with V's own block, its parameter column and W's block in one
// plain run (AcrossVariations with its inside block): on the row setup 4 + 16 + 4 + 4 = 28 entries
// instead of 6 + 36 + 6 = 48, the in-phase k-branch at the default preset 1.81 -> 1.16 CPU s. And
// a plain residual integrates the orbit in V alone (4 states instead of 6: 1.16 -> 1.12 s, single
// runs alternated three times). Each time, provided:
//   - the point is in V to 1e-13 of its size (the corrector's steps leave it there only to
//     rounding, ~1e-16): its part in V is integrated, and the residual with derivatives is
//     corrected to first order by the monodromy for the rest; the plain residual leaves it out;
//   - f keeps the reflection at p (equivariance_defect below 1e-12), and with a parameter column
//     so does df/dp (a parameter that detunes the reflection, such as one metronome's length,
//     moves the orbit off V and gets the whole computation).
// Otherwise (several segments, a point off V, the forward module) the whole computation runs, as
// without symmetry.
#pragma once

#include <map>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "sympathy/core/flow.hpp"
#include "sympathy/core/invariant_subspace.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy {

struct ShootingOptions {
  int segments = 1;  // 1 to 1000
  // Threads that integrate the segments side by side (1 to 256; more than `segments` are not
  // used). Each segment is integrated from its own start by a flow of its own thread, restarted
  // at each call, so the result is the same to the bit for any number of threads.
  int threads = 1;
  FlowOptions flow;

  OptionCheck validate() const {
    if (segments < 1 || segments > 1000)
      return OptionProblem{"segments", "an integer from 1 to 1000"};
    if (threads < 1 || threads > 256) return OptionProblem{"threads", "an integer from 1 to 256"};
    return nested("flow.", flow.validate());
  }
};

// One period of an orbit sampled at T k / intervals, k = 0 .. intervals (both ends), by the run
// with sensitivities that confirmed it: what the branch's scales and the describers read instead
// of integrating the period once more (on the anti-phase k-branch those two plain runs per point
// were 23% of the fast preset's time and 10% of the default's).
// The phase condition's Poincare section: the hyperplane through `through` normal to `normal`
// (f(through; p), or f in a chosen metric: BranchSpace::section). It belongs to the point whose
// unknowns it fixes in time and travels with it: each evaluation is made in the section it is
// given and carries it, so that a residual and its Jacobian agree wherever they are used, and no
// caller depends on what another left in the problem. Empty: no phase row (a forced system, or a
// caller with a phase condition of its own); its row is then zero.
struct PhaseSection {
  Eigen::VectorXd through;
  Eigen::VectorXd normal;
  // <normal, z0 - through>: the phase condition's residual at a first state z0.
  double offset(const Eigen::VectorXd& z0) const {
    return through.size() ? normal.dot(z0 - through) : 0.0;
  }
  bool operator==(const PhaseSection& o) const {
    return through.size() == o.through.size() && normal.size() == o.normal.size() &&
           through == o.through && normal == o.normal;
  }
};

struct PeriodSamples {
  static constexpr int intervals = 800;
  double period = 0.0;
  Eigen::MatrixXd states;  // n x (intervals + 1); empty: none
  // Whether these are samples of the orbit through z0 with this period (exactly: an orbit whose
  // state was mapped afterwards, reflected or lifted, no longer has them).
  bool of(const Eigen::VectorXd& z0, double T) const {
    return states.cols() == intervals + 1 && states.rows() == z0.size() && period == T &&
           states.col(0) == z0;
  }
};

class ShootingProblem {
 public:
  // `forced_period`: the period of a non-autonomous system (ignored for autonomous ones).
  ShootingProblem(const OdeSystem& system, ShootingOptions options, double forced_period = 0.0);
  ~ShootingProblem();

  // Orbits lying in `subspace` may reuse the last evaluation with derivatives and integrate only
  // the block across it (see the header comment), where the subspace is the fixed space of a
  // reflection; otherwise (or with the whole space) this does nothing.
  void use_symmetry(const InvariantSubspace& subspace);
  // Evaluations with derivatives served that way since the last reset_statistics().
  int across_evaluations() const;
  // Evaluations with derivatives of an orbit in the subspace that the parameter moves, integrated
  // block by block (see the header comment), since the last reset_statistics().
  int split_evaluations() const;

  // A branch in the symmetric subspace V (use_symmetry) kept there exactly: the unknowns' state
  // (the head of `unknowns`) replaced by its part in V where it lies in V to 1e-13 of its size
  // and f keeps the reflection at p (as the split and across evaluations ask); true if so
  // (nothing changes otherwise), and then the point's tangent belongs in V too
  // (project_on_subspace). Each step leaves a branch in V only to rounding, and steps whose
  // prediction lands (no corrector iteration) never pull it back: the row setup's in-phase
  // k-branch drifted past 1e-13 after 21 points and lost its split evaluations.
  bool keep_in_subspace(Eigen::VectorXd& unknowns, const ParameterValues& p) const;
  // The state part (the head) of a direction of the unknowns replaced by its part in V.
  void project_on_subspace(Eigen::VectorXd& direction) const;

  int segments() const { return options_.segments; }
  Method method() const { return options_.flow.method; }
  int dimension() const { return n_; }
  int unknowns() const { return n_ * options_.segments + (autonomous_ ? 1 : 0); }
  bool autonomous() const { return autonomous_; }
  const OdeSystem& system() const { return system_; }

  // The section through z normal to the flow there, f(z; p).
  PhaseSection section_through(const Eigen::VectorXd& z, const ParameterValues& p) const;

  // Unknowns from an initial state and period: the segment states by integrating one period.
  // Also sets the winding: what each angle gains over the period, rounded to a multiple of 2 pi.
  Eigen::VectorXd unknowns_from(const Eigen::VectorXd& z0, const ParameterValues& p, double period);
  // The same from the states at k equal times over the period (the columns of `starts`, k
  // dividing the segments): each given state kept, the segments' starts between them integrated
  // from it segment by segment, so that an orbit whose perturbations grow by 1e12 over the period
  // is re-sampled with errors of one old segment's growth only (AUTO's ab at p2 = 16: from one
  // integration, no correction on 8 segments). With one start, unknowns_from.
  Eigen::VectorXd unknowns_from_starts(const Eigen::MatrixXd& starts, const ParameterValues& p,
                                       double period);
  // What the states gain over one period: 2 pi k on the angles that rotate, 0 elsewhere.
  const Eigen::VectorXd& winding() const { return winding_; }
  void set_winding(const Eigen::VectorXd& winding) { winding_ = winding; }
  double period(const Eigen::VectorXd& x) const;
  Eigen::VectorXd state(const Eigen::VectorXd& x, int segment = 0) const {
    return x.segment(segment * n_, n_);
  }

  struct Evaluation {
    Eigen::VectorXd residual;
    ParameterValues parameters;  // where it was evaluated
    PhaseSection section;        // in which (the phase row of the residual and the Jacobian)
    bool derivatives = false;
    std::vector<Eigen::MatrixXd> transitions;  // per segment, dPhi/dz_j
    std::vector<Eigen::VectorXd> end_rates;    // per segment, f at its end
    Eigen::MatrixXd parameter_sensitivities;   // n x m: dPhi/dp per segment (if asked)
    int parameter = -1;
    PeriodSamples samples;  // with derivatives and record_samples: the period's states
  };
  // Evaluations with derivatives also sample the period (PeriodSamples) on the way, from their
  // steps' interpolants: 801 interpolations, about a tenth of a plain run of the period.
  void record_samples(bool on) { record_samples_ = on; }
  // Residual at parameter values p in `section`, and with `derivatives` the transition matrices
  // (and dPhi/dp for the named parameter `parameter`). Throws IntegrationError if a segment
  // cannot be integrated.
  Evaluation evaluate(const Eigen::VectorXd& x, const ParameterValues& p,
                      const PhaseSection& section, bool derivatives, int parameter = -1);
  // The same evaluation of x in another section (a continuation moves its section to a point it
  // accepted): the phase row's residual changes, nothing is integrated.
  void move_to_section(Evaluation& e, const Eigen::VectorXd& x, PhaseSection section) const;
  // The residual alone, from plain integrations as accurate as those with derivatives.
  // `coarse`: at a thousand times the tolerances, for a Newton-like step far from the solution,
  // where the residual is large against that run's error (CorrectorOptions::coarse_above).
  Eigen::VectorXd residual(const Eigen::VectorXd& x, const ParameterValues& p,
                           const PhaseSection& section, bool coarse = false);

  // d(residual)/dx as a sparse matrix (in the evaluation's section), rows = unknowns(); with
  // `parameter_column` the column
  // d(residual)/dp appended (the evaluation must carry it).
  Eigen::SparseMatrix<double> jacobian(const Evaluation& e, bool parameter_column = false) const;

  // Work of all integrations, with and without derivatives.
  FlowStatistics statistics() const;
  void reset_statistics();

 private:
  const OdeSystem& system_;
  ShootingOptions options_;
  int n_;
  bool autonomous_;
  double forced_period_;
  Flow flow_;                             // integrations with derivatives, unknowns_from
  std::unique_ptr<Flow> plain_flows_[2];  // residual(): tightened, and coarse; made on first use

  Evaluation evaluate(const Eigen::VectorXd& x, const ParameterValues& p, bool derivatives,
                      int parameter, Flow& flow);
  // The flows that integrate segments beside `flow` on the other threads (options_.threads):
  // made on first use with `flow`'s system and options, kept per flow.
  std::map<const Flow*, std::vector<std::unique_ptr<Flow>>> helpers_;
  std::vector<Flow*> team(Flow& flow);
  struct SymmetricOrbit;  // shooting.cpp
  std::unique_ptr<SymmetricOrbit> symmetric_;
  std::optional<Evaluation> across_evaluation(const Eigen::VectorXd& x, const ParameterValues& p,
                                              int parameter);
  FlowOptions plain_options(bool coarse) const;  // residual()'s: tightened, or coarse
  // z's part in the symmetric subspace V, where z is in V to 1e-13 and f keeps the reflection at
  // p (what split_evaluation and residual_in_subspace both need); nullopt otherwise.
  std::optional<Eigen::VectorXd> symmetric_part(const Eigen::VectorXd& z,
                                                const ParameterValues& p) const;
  Eigen::VectorXd in_subspace(const Eigen::VectorXd& z) const;  // z's part in V, exactly in V
  std::optional<Eigen::VectorXd> residual_in_subspace(const Eigen::VectorXd& x,
                                                      const ParameterValues& p, bool coarse);
  std::optional<Evaluation> split_evaluation(const Eigen::VectorXd& x, const ParameterValues& p,
                                             int parameter);
  void remember(const Eigen::VectorXd& x, const Evaluation& e);
  Eigen::VectorXd winding_;  // n: 2 pi k per rotating angle
  bool record_samples_ = false;
};

}  // namespace sympathy
