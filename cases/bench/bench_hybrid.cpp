// Section (l) of sympathy bench. The two escapements are two models, so each is measured against
// its own reference (BDF rtol 1e-13, as sections (a) and (b)), never against the other: their
// orbits differ by far more than any integrator's error (docs/accuracy.md, "The smoothed
// escapement against the paper's": 1.4e-4 s in the in-phase period at Table III). Each setting
// solves the orbit by Newton from the same guess (sections (a) and (b)'s), which gives its errors;
// its cost is one period with the monodromy (every state column) from the solved orbit at the
// same setting, the unit a continuation point and a Newton iteration repeat. The comparison at
// equal error asks both models for the same errors and reads off the cost per period at which
// each sweep first reaches them.
// Measured (2026-11-29, one core of the 2-core machine, the whole section in 1.2 s): at a period
// error of 1e-8 and multipliers of 1e-7 a hybrid period cost 0.34 to 0.45 times the smoothed
// one's CPU time with Adams and 0.60 to 0.64 with Dormand-Prince, at 1e-10 and 1e-8 0.37 to 0.67;
// the steps in about the same ratios (a step costs about as much on both: 1.9 against 1.6 to
// 1.75 us with Adams). The smoothed model's capped steps through its turning-point pulses are what
// the hybrid flow saves; its 10 restarts a period cost less. Timing one period from the solved
// orbit rather than the solve: the solves take 2 or 3 Newton iterations on either model (5 for
// the smoothed anti-phase orbit at rtol 1e-6), so their times mix the iteration count into the
// cost per period.
#include "cases/bench/bench_hybrid.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "cases/bench/bench_orbit.hpp"
#include "cases/cli/common.hpp"
#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"

namespace sympathy::bench {

using namespace sympathy::cli;  // the program's options, progress line and interrupts

namespace {

// The stated errors of the comparison: the period (relative) and the nontrivial multipliers; the
// second is reached by the smoothed model's Adams sweep only at its tightest setting.
struct ErrorTarget {
  double period, multipliers;
};
constexpr ErrorTarget kTargets[] = {{1e-8, 1e-7}, {1e-10, 1e-8}};

struct ModelChoice {
  const char* name;
  Escapement escapement;
};
constexpr ModelChoice kModels[] = {{"smoothed", Escapement::Half},
                                   {"impulsive", Escapement::Impulsive}};

// One setting on one model: the solve's errors and the cost of one period at the solved orbit.
struct Measured {
  Setting setting;
  Result solve;
  double period_error = NAN;      // relative
  double multiplier_error = NAN;  // the largest distance, nontrivial multipliers
  double period_seconds = NAN;    // CPU, one period with the monodromy, median of repeats
  double period_steps = NAN;
  long period_switchings = 0;  // restarts at switching surfaces in that period (hybrid only)
};

// How far a setting is from a stated error: the larger of its two errors over its target (1 or
// less: reached).
double shortfall(const Measured& m, const ErrorTarget& target) {
  if (!m.solve.converged) return NAN;
  return std::max(m.period_error / target.period, m.multiplier_error / target.multipliers);
}

// The cost per period at which a sweep (loose to tight) first reaches the stated error: log cost
// interpolated linearly in log shortfall between the last setting short of it and the first that
// reaches it. Reached already at the loosest setting: its cost, an upper bound.
struct CostAtTarget {
  double seconds = NAN, steps = NAN;
  bool upper_bound = false;  // the loosest setting reached it
};

CostAtTarget cost_at_target(const std::vector<Measured>& sweep, const ErrorTarget& target) {
  CostAtTarget c;
  for (std::size_t i = 0; i < sweep.size(); ++i) {
    const double s = shortfall(sweep[i], target);
    if (!(s <= 1.0)) continue;
    const double before = i > 0 ? shortfall(sweep[i - 1], target) : NAN;
    if (!(before > 1.0) || !(s > 0.0)) {
      c.seconds = sweep[i].period_seconds;
      c.steps = sweep[i].period_steps;
      c.upper_bound = true;
      return c;
    }
    const double t = std::log(before) / (std::log(before) - std::log(s));
    auto between = [t](double a, double b) { return std::exp(std::log(a) + t * std::log(b / a)); };
    c.seconds = between(sweep[i - 1].period_seconds, sweep[i].period_seconds);
    c.steps = between(sweep[i - 1].period_steps, sweep[i].period_steps);
    return c;
  }
  return c;
}

std::string cost_text(const CostAtTarget& c, double v, const char* format) {
  if (!std::isfinite(v)) return "not reached";
  return (c.upper_bound ? "<= " : "") + table_number(v, format);
}

// One period with every state column from the solved orbit, at the setting's flow.
void time_one_period(const MetronomeModel& model, const ParameterValues& p, Measured& m,
                     int repeats) {
  if (!m.solve.converged) return;
  Flow flow(model, m.setting.flow);
  m.period_seconds = median_cpu_seconds(repeats, [&] {
    flow.reset_statistics();
    flow.advance_with_sensitivities(m.solve.state0, p, 0.0, m.solve.period);
  });
  m.period_steps = static_cast<double>(flow.statistics().steps);
  m.period_switchings = flow.statistics().switchings;
}

struct Sweep {
  std::string name;
  Setting (*make)(const std::string& name, double rtol);
  std::vector<double> tolerances;  // loose to tight
};

// The default preset's integrator (accuracy.cpp): Adams with fixed-point iteration on the state
// and its variational equations as one system.
Setting adams_augmented(const std::string& name, double rtol) {
  Setting s = setting(name, Method::Adams, rtol);
  s.flow.sensitivities = Sensitivities::Augmented;
  return s;
}

// The fast preset's: Dormand-Prince 5(4) on the same augmented system (its turning-point caps at
// the library's fraction, not the preset's 0.6, so that both models' flows differ in nothing
// else).
Setting dormand_prince(const std::string& name, double rtol) {
  Setting s = setting(name, Method::ERK, rtol);
  s.flow.sensitivities = Sensitivities::Augmented;
  s.flow.explicit_table = ExplicitTable::DormandPrince;
  return s;
}

}  // namespace

void bench_hybrid(const std::string& root, bool quick, CsvWriter& csv, std::ostream& md) {
  const CaseFile file = CaseFile::load(root + "cases/row2.toml");
  const int repeats = quick ? 5 : 9;
  std::vector<Sweep> methods{{"Adams, augmented", adams_augmented,
                              quick ? std::vector<double>{1e-6, 1e-8, 1e-10, 1e-11}
                                    : std::vector<double>{1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11}}};
  if (!quick)
    methods.push_back({"Dormand-Prince", dormand_prince, {1e-6, 1e-7, 1e-8, 1e-9, 1e-10}});
  struct Problem {
    std::string name, params, start;
  };
  const std::vector<Problem> problems{{"(l) anti-phase orbit, Table II", "table2", "anti-phase"},
                                      {"(l) in-phase orbit, Table III", "table3", "in-phase"}};

  md << "\n## (l) the paper's impulsive escapement (hybrid orbits) against the smoothed one\n\n"
        "The smoothed escapement (eq. 3, eps = 0.05, the turning-point pulse resolved by step "
        "caps) and the paper's impulsive one (eq. 2: the flow restarts at each switching-surface "
        "crossing and carries the sensitivities across by saltation matrices), each against its "
        "own reference (BDF rtol 1e-13; its change from rtol 1e-12 is the level below which "
        "errors are not resolved). Each setting solves the orbit by Newton from the same guess "
        "(the orbit moved by 1e-3); its cost is one period with the monodromy (every state "
        "column) from the solved orbit at the same setting, CPU time (median of "
     << repeats
     << ") and steps. Multiplier error: the largest distance of the nontrivial multipliers "
        "from the reference's, paired by least total squared distance (here: sorted by "
        "modulus, each member of a complex pair with its own).\n";
  // The cost at a stated error, per problem, method and target: smoothed, impulsive.
  struct Comparison {
    std::string problem, method;
    ErrorTarget target;
    CostAtTarget smoothed, impulsive;
  };
  std::vector<Comparison> comparisons;
  for (const auto& p : problems) {
    md << "\n### " << p.name.substr(4) << "\n\n";
    std::vector<std::vector<std::vector<Measured>>> sweeps;  // [model][method][setting]
    std::string references;
    std::ostringstream table;
    for (const ModelChoice& choice : kModels) {
      ModelSpec spec = file.spec(p.params);
      spec.escapement = choice.escapement;
      const MetronomeModel model(spec);
      const StartSpec& start = file.start(p.start);
      const InvariantSubspace subspace = file.invariant_subspace(start, model);
      const PeriodicOrbit guess = orbit_guess(model, file, start, subspace);
      const Result ref = solve_orbit(model, guess, subspace, reference_setting());
      const Result chk = solve_orbit(model, guess, subspace, check_setting());
      if (!ref.converged || !chk.converged)
        throw std::runtime_error("bench (l): the " + std::string(choice.name) + " reference of " +
                                 p.name + " did not converge: " + ref.note + chk.note);
      const double floor_period = std::abs(chk.period - ref.period) / ref.period;
      const double floor_mu = multiplier_error(chk.multipliers, ref.multipliers);
      references += std::string(references.empty() ? "" : "; ") + choice.name + " period " +
                    table_number(ref.period, "%.13f") +
                    " s (change from rtol 1e-12: " + table_number(floor_period, "%.1e") +
                    ", multipliers " + table_number(floor_mu, "%.1e") + ")";
      std::printf(
          "%s, %s: reference period %.13f s (rtol 1e-12 differs by %.1e, multipliers "
          "%.1e)\n",
          p.name.c_str(), choice.name, ref.period, floor_period, floor_mu);
      std::fflush(stdout);
      sweeps.emplace_back();
      for (const Sweep& method : methods) {
        sweeps.back().emplace_back();
        for (double rtol : method.tolerances) {
          Measured m;
          m.setting = method.make(std::string(choice.name) + ": " + method.name, rtol);
          m.solve = solve_orbit(model, guess, subspace, m.setting);
          if (m.solve.converged) {
            m.period_error = std::abs(m.solve.period - ref.period) / ref.period;
            m.multiplier_error = multiplier_error(m.solve.multipliers, ref.multipliers);
          }
          time_one_period(model, guess.parameters, m, repeats);
          csv.row(orbit_csv_row(p.name, m.setting, m.solve, m.period_error, m.multiplier_error, NAN,
                                m.period_seconds, m.period_steps));
          table << "| " << m.setting.name << " | " << table_number(rtol, "%.0e") << " | "
                << table_number(m.period_error, "%.2e") << " | "
                << table_number(m.multiplier_error, "%.2e") << " | "
                << table_number(m.solve.trivial_error, "%.2e") << " | "
                << table_number(1e3 * m.period_seconds, "%.3f") << " | "
                << table_number(m.period_steps, "%.0f") << " | " << m.period_switchings << " | "
                << table_number(m.solve.seconds, "%.3f") << " | " << m.solve.iterations << " | "
                << (m.solve.converged ? "" : "not converged: " + m.solve.note) << " |\n";
          std::printf(
              "  %-28s rtol %.0e  period %s  multipliers %s  trivial %s  %.3f ms, %.0f "
              "steps a period%s\n",
              m.setting.name.c_str(), rtol, table_number(m.period_error, "%.2e").c_str(),
              table_number(m.multiplier_error, "%.2e").c_str(),
              table_number(m.solve.trivial_error, "%.2e").c_str(), 1e3 * m.period_seconds,
              m.period_steps, m.solve.converged ? "" : "  (not converged)");
          std::fflush(stdout);
          sweeps.back().back().push_back(m);
        }
      }
    }
    md << "References (BDF rtol 1e-13): " << references << ".\n\n"
       << "| model: integrator | rtol | period error (rel.) | multiplier error | trivial error | "
          "CPU ms / period | steps / period | switchings / period | solve (s) | Newton iterations "
          "| "
          "|\n"
       << "|---|---|---|---|---|---|---|---|---|---|---|\n"
       << table.str();
    for (const ErrorTarget& target : kTargets)
      for (std::size_t k = 0; k < methods.size(); ++k)
        comparisons.push_back({p.name.substr(4), methods[k].name, target,
                               cost_at_target(sweeps[0][k], target),
                               cost_at_target(sweeps[1][k], target)});
  }

  md << "\n### At equal error\n\nThe cost of one period each model needs to reach a stated "
        "period error (relative) and multiplier error against its own reference, interpolated on "
        "log-log between the last setting of a sweep that misses either and the first that meets "
        "both (\"<=\": the loosest setting meets them already; \"~\": a ratio that rests on such "
        "a bound). A ratio below 1: the hybrid path reaches that error for less per period than "
        "the smoothed model; above 1, for more.\n\n"
        "| orbit | integrator | period, multipliers | smoothed: CPU ms / period | steps / period "
        "| impulsive: CPU ms / period | steps / period | impulsive / smoothed (CPU) | (steps) |\n"
        "|---|---|---|---|---|---|---|---|---|\n";
  double lowest = INFINITY, highest = -INFINITY, lowest_steps = INFINITY, highest_steps = -INFINITY;
  int unreached = 0;
  for (const Comparison& c : comparisons) {
    const double seconds = c.impulsive.seconds / c.smoothed.seconds;
    const double steps = c.impulsive.steps / c.smoothed.steps;
    const bool bound = c.smoothed.upper_bound || c.impulsive.upper_bound;
    if (std::isfinite(seconds)) {
      lowest = std::min(lowest, seconds);
      highest = std::max(highest, seconds);
      lowest_steps = std::min(lowest_steps, steps);
      highest_steps = std::max(highest_steps, steps);
    } else {
      ++unreached;
    }
    const std::string target =
        table_number(c.target.period, "%.0e") + ", " + table_number(c.target.multipliers, "%.0e");
    md << "| " << c.problem << " | " << c.method << " | " << target << " | "
       << cost_text(c.smoothed, 1e3 * c.smoothed.seconds, "%.3f") << " | "
       << cost_text(c.smoothed, c.smoothed.steps, "%.0f") << " | "
       << cost_text(c.impulsive, 1e3 * c.impulsive.seconds, "%.3f") << " | "
       << cost_text(c.impulsive, c.impulsive.steps, "%.0f") << " | "
       << table_number(seconds, bound ? "~%.2f" : "%.2f") << " | "
       << table_number(steps, bound ? "~%.2f" : "%.2f") << " |\n";
    std::printf(
        "(l) %s, %s, at period error %s and multipliers %s: smoothed %s ms and %s steps "
        "a period, impulsive %s ms and %s steps; impulsive / smoothed %s (CPU), %s "
        "(steps)\n",
        c.problem.c_str(), c.method.c_str(), table_number(c.target.period, "%.0e").c_str(),
        table_number(c.target.multipliers, "%.0e").c_str(),
        cost_text(c.smoothed, 1e3 * c.smoothed.seconds, "%.3f").c_str(),
        cost_text(c.smoothed, c.smoothed.steps, "%.0f").c_str(),
        cost_text(c.impulsive, 1e3 * c.impulsive.seconds, "%.3f").c_str(),
        cost_text(c.impulsive, c.impulsive.steps, "%.0f").c_str(),
        table_number(seconds, "%.2f").c_str(), table_number(steps, "%.2f").c_str());
  }
  // What the ratios say, from the ratios themselves.
  md << "\n";
  if (std::isfinite(lowest))
    md << "Measured: at equal error the hybrid path costs " << table_number(lowest, "%.2f")
       << " to " << table_number(highest, "%.2f")
       << " times the smoothed model's CPU time per period (" << table_number(lowest_steps, "%.2f")
       << " to " << table_number(highest_steps, "%.2f") << " times its steps): "
       << (highest <= 1.0 ? "no more than the smoothed model's on every problem and integrator."
           : lowest > 1.0 ? "more than the smoothed model's on every problem and integrator."
                          : "less on some problems or integrators and more on others.");
  if (unreached > 0)
    md << (std::isfinite(lowest) ? " " : "") << unreached
       << " comparison(s) without a ratio: a sweep did not reach the stated error.";
  md << "\n";
  std::fflush(stdout);
}

}  // namespace sympathy::bench
