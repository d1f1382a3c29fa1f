#include "cases/app/option_table.hpp"

#include "sympathy/core/errors.hpp"

namespace sympathy::app {

std::vector<OptionSpec> case_options() {
  return {
      {"--params", "NAME", false, "named parameter set of the case (default: the file's)"},
      {"--set", "KEY=VALUE", true, "set a parameter of the case to a value"},
  };
}

std::vector<OptionSpec> integrator_options() {
  return {
      {"--rtol", "R", false,
       "relative tolerance of the integrator (default: 5e-12 for orbits, branches and curves, the "
       "--accuracy preset's; 1e-8 for simulations; 1e-9 for fits)"},
      {"--atol", "A", false,
       "absolute tolerance of the integrator (default: 5e-14 for orbits, branches and curves, the "
       "--accuracy preset's; 1e-10 for simulations; 1e-11 for fits)"},
      {"--method", "bdf|adams|erk", false,
       "integration method: CVODES's BDF or Adams, or ARKODE's explicit Runge-Kutta "
       "(Dormand-Prince 5(4); with it the sensitivities are augmented) (default: adams for orbits, "
       "branches and curves, the --accuracy preset's, switched to bdf where the start measures "
       "stiff; bdf for simulations and fits; given, it is used whatever the stiffness)"},
      {"--sensitivities", "forward|augmented", false,
       "how the monodromy is integrated: CVODES's forward-sensitivity module, or the variational "
       "equations appended to the state (default: augmented for orbits, branches and curves, the "
       "--accuracy preset's; forward for fits)"},
      {"--linear-solver", "dense|klu|structured", false,
       "linear solver of the BDF Newton iteration (default: structured, sparse plus low rank, for "
       "more than 3 metronomes; else dense)"},
  };
}

OptionSpec accuracy_option() {
  return {"--accuracy", "fast|default|high", false,
          "integrator preset: fast = explicit Runge-Kutta at rtol 1e-8 and coarser branch steps, "
          "located points within 4e-7; default = Adams at rtol 5e-12, located points within "
          "1e-8; high = tighter (default: default; where a command takes --rtol, --method or "
          "--sensitivities, they override it)"};
}

OptionSpec segment_threads_option() {
  return {"--threads", "N", false,
          "threads integrating the shooting segments side by side (default: one per core; the "
          "result is the same for any number)"};
}

// The longest period a transient's start looks for (OrbitOptions::max_period).
OptionSpec max_period_option() {
  return {"--max-period", "SECONDS", false,
          "the longest period looked for after the transient (default 10): a start whose orbit "
          "is slower needs more"};
}

// A start from an earlier run's saved orbit (AUTO's IRS), with --parent.
OptionSpec from_point_option() {
  return {"--from-point", "POINT", false,
          "start from this point of the --parent branch (its index, points[].index of the JSON) "
          "or its event (LP1, BP1, PD1, NS1, UZ1, ...), or from a point of a --parent curve (curve "
          "--json, by index): the saved orbit's state, period, segments and parameter values, "
          "corrected at once (AUTO's IRS)"};
}

OptionSpec start_data_option() {
  return {"--start-data", "FILE.csv", false,
          "start from one recorded period instead (columns t and every state, as simulate --out "
          "writes; its first row the start, its span or first return the period guess)"};
}

// Newton at once from the start state with a period guess (no transient).
OptionSpec period_guess_option() {
  return {"--period-guess", "SECONDS", false,
          "Newton at once from the start state (--start, --initial) with this period, no "
          "transient: an unstable orbit, or one of several loops, from a state on it"};
}

// AUTO's dat files: time scaled to [0, 1], the period given beside them.
OptionSpec data_period_option() {
  return {"--data-period", "SECONDS", false,
          "with --start-data: its time column is scaled to [0, 1] over one period (AUTO's dat "
          "files), and this is the period"};
}

std::vector<OptionSpec> branch_step_options() {
  return {{"--segments", "M", false, "shooting segments (default 1)"},
          {"--step", "DS", false, "initial arclength step, scaled (default 0.02)"},
          {"--max-step", "DS", false, "largest arclength step, scaled (default 0.1)"},
          {"--max-points", "N", false, "point limit per direction (default 400)"},
          {"--transient", "SECONDS", false,
           "integration before the first Newton (default 60; 0 for a forced system)"},
          max_period_option()};
}

std::vector<OptionSpec> continue_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--start", "NAME", false,
        "named start of the case (required for a metronome case file; an equation case file's "
        "default: its [states])"},
       {"--param", "P", false, "the continuation parameter, one of the case's", true},
       {"--from", "A", false, "first parameter value: the branch starts here", true},
       {"--to", "B", false, "last parameter value", true},
       {"--at", "V", false, "start at V instead and continue both ways, to A and to B"},
       {"--initial", "VAR=VALUE", true, "initial state value (on top of --start)"},
       {"--user-points", "V1,V2,...", false,
        "report the branch's orbit at each of these values of --param (AUTO's UZ), as events"},
       {"--user-value", "QUANTITY=VALUE", true,
        "report the branch's orbit where a quantity of its orbits takes this value, as an event "
        "(AUTO's UZ on any quantity): period, max_NAME or min_NAME (a state's largest or "
        "smallest value over the period), or NAME (its value at the orbit's point on its "
        "section, state0)"},
       {"--stop-at", "QUANTITY=VALUE", true, "the same, and the branch ends there (AUTO's UZSTOP)"},
       {"--csv", "FILE", false, "stream every point to this CSV"},
       {"--json", "FILE", false, "write the branch and its bifurcations as JSON"},
       {"--events", "FILE", false, "stream each bifurcation to this CSV as it is located"},
       {"--switch-at", "EVENT", false,
        "continue the branch born at this event instead (BP1, PD1, ...: the first BP, ...; "
        "HB1: the family born at the first Hopf point of the equilibria through the start)"},
       {"--hopf-amplitude", "A", false,
        "with --switch-at HBn: the first orbit's amplitude along the critical eigenvector's real "
        "part, in state units (default: 2% of the state's size, grown where the family is "
        "nearly vertical, shrunk where Newton fails)"},
       {"--parent", "FILE", false,
        "with --switch-at: the parent branch from this JSON (continue --json; for HB, equilibria "
        "--json) instead of computed; with --from-point: the branch or curve JSON the start is "
        "saved in"},
       {"--whole-state", "", false,
        "no symmetry reduction: integrate every metronome (for comparison)"},
       {"--quiet", "", false, "no progress lines"},
       {"--verbose", "", false, "multipliers on each progress line; the full report at the end"}});
  const auto steps = branch_step_options();
  options.insert(options.end(), steps.begin(), steps.end());
  options.push_back(segment_threads_option());
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  options.push_back(accuracy_option());
  options.push_back(start_data_option());
  options.push_back(data_period_option());
  options.push_back(from_point_option());
  options.push_back(period_guess_option());
  return options;
}

std::vector<OptionSpec> orbit_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--start", "NAME", false, "named start of the case (required for a metronome case file)"},
       {"--initial", "VAR=VALUE", true, "initial state value (on top of --start)"},
       {"--segments", "M", false, "shooting segments (default 1: single shooting)"},
       segment_threads_option(),
       {"--transient", "SECONDS", false,
        "integration before Newton (default 60; 0 for a forced system)"},
       max_period_option(),
       {"--json", "FILE", false, "write the orbit as JSON"},
       {"--whole-state", "", false,
        "no symmetry reduction: integrate every metronome (for comparison)"},
       {"--verbose", "", false, "the full report: Newton steps, integration work"}});
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  options.push_back(accuracy_option());
  options.push_back(start_data_option());
  options.push_back(data_period_option());
  options.push_back(
      {"--parent", "FILE", false,
       "with --from-point: the branch or curve JSON (continue or curve --json) the start is "
       "saved in"});
  options.push_back(from_point_option());
  options.push_back(period_guess_option());
  return options;
}

std::vector<OptionSpec> simulate_options() {
  auto options = case_options();
  options.insert(options.end(),
                 {{"--start", "NAME", false, "named start of the case (in-phase, ...)"},
                  {"--initial", "VAR=VALUE", true, "initial state value (on top of --start)"},
                  {"--t-end", "SECONDS", false, "end time (default 60)"},
                  {"--dt", "SECONDS", false, "output interval (default 0.01)"},
                  {"--locked-pendula", "", false,
                   "pendula fixed to their casings: the platform alone (states x, vx)"},
                  {"--out", "FILE.csv", false, "write the time series here"},
                  {"--verbose", "", false, "the full report of the integration's work"}});
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  return options;
}

std::vector<OptionSpec> equilibria_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--start", "NAME", false,
        "named start of the case, Newton's first guess (required for a metronome case file; an "
        "equation case file's default: its [states])"},
       {"--param", "P", false, "the continuation parameter, one of the case's", true},
       {"--from", "A", false, "first parameter value: the branch starts here", true},
       {"--to", "B", false, "last parameter value", true},
       {"--at", "V", false, "start at V instead and continue both ways, to A and to B"},
       {"--initial", "VAR=VALUE", true, "initial state value (on top of --start)"},
       {"--user-points", "V1,V2,...", false,
        "report the branch's equilibrium at each of these values of --param (AUTO's UZ), as "
        "events"},
       {"--switch-at", "EVENT", false,
        "continue the branch of equilibria born at this branch point of the equilibria through "
        "the start instead (BP1, BP2, ...), both ways from it within --from .. --to"},
       {"--parent", "FILE", false,
        "with --switch-at: the parent equilibria from this JSON (equilibria --json) instead of "
        "computed; with --from-point: the equilibria JSON the start is saved in"},
       {"--from-point", "POINT", false,
        "start from this point of the --parent equilibria (its index, points[].index of the "
        "JSON) or its event (LP1, BP1, HB1, UZ1, ...): its state and every parameter value "
        "(AUTO's IRS)"},
       {"--step", "DS", false, "initial arclength step, scaled (default 0.01)"},
       {"--max-step", "DS", false, "largest arclength step, scaled (default 0.05)"},
       {"--max-points", "N", false, "point limit per direction (default 1000)"},
       {"--csv", "FILE", false, "stream every point to this CSV"},
       {"--json", "FILE", false,
        "write the branch and its events as JSON (continue --switch-at HB1 --parent reads it)"},
       {"--quiet", "", false, "no progress lines"}});
  return options;
}

std::vector<OptionSpec> curve_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--start", "NAME", false,
        "named start of the case (required for a metronome case file; an equation case file's "
        "default: its [states])"},
       {"--param", "P", false, "the branch's parameter, the curve's first", true},
       {"--from", "A", false, "the branch's first value, one end of the window", true},
       {"--to", "B", false, "the branch's last value, the window's other end", true},
       {"--initial", "VAR=VALUE", true, "initial state value (on top of --start)"},
       {"--transient", "SECONDS", false, "integration before the first Newton (default 60)"},
       {"--parent", "FILE", false,
        "the branch from this JSON (continue --json) instead; or equilibria (equilibria --json): "
        "then the fold or Hopf curve of equilibria from their LPn or HBn; or a Hopf curve of "
        "equilibria (curve --json): then the fold of cycles born at its GHn"},
       {"--event", "EVENT", false,
        "the event whose curve to follow: LP1, BP1, NS2, ... (of equilibria: LP1, HB1, ...; of a "
        "Hopf curve: GH1, ...)",
        true},
       {"--second", "Q", false, "the second parameter", true},
       {"--second-from", "A", false, "the window in the second parameter ...", true},
       {"--second-to", "B", false, "... and its other end", true},
       {"--step", "DS", false, "initial arclength step, scaled (default 0.01)"},
       {"--max-step", "DS", false, "largest arclength step, scaled (default 0.05)"},
       {"--max-points", "N", false, "point limit per direction (default 200)"},
       {"--user-value", "QUANTITY=VALUE", true,
        "report the curve's point where its period (period=VALUE) or either of its parameters "
        "(NAME=VALUE) takes this value, as an event UZ (AUTO's UZ); a curve of equilibria's, its "
        "parameters only"},
       {"--stop-at", "QUANTITY=VALUE", true, "the same, and the curve ends there (AUTO's UZSTOP)"},
       {"--csv", "FILE", false, "stream every curve point to this CSV"},
       {"--json", "FILE", false, "write the curve and its codimension-two points as JSON"},
       {"--quiet", "", false, "no progress lines"}});
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  options.push_back(accuracy_option());
  options.push_back(start_data_option());
  options.push_back(data_period_option());
  return options;
}

std::vector<OptionSpec> study_options() {
  return {{"--out", "DIR", false, "where the CSV and JSON files go (default out/figures)"},
          {"--jobs", "N", false, "branches computed side by side (default 2)"},
          {"--resume", "", false,
           "continue the [basins] walk from its journal in --out (the runs it holds are not run "
           "again)"},
          {"--quiet", "", false, "no progress line on a terminal"},
          accuracy_option()};
}

std::vector<OptionSpec> fit_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--data", "FILE.csv", false, "the recording: columns t and state names", true},
       {"--free", "NAME[,NAME...]", true, "parameters of the case to fit"},
       {"--free-initial", "VAR[,VAR...]", true, "initial values of the case's states to fit too"},
       {"--locked-pendula", "", false,
        "a metronome case's pendula fixed to their casings: the platform alone"},
       {"--start", "NAME", false, "unrecorded states start from this named start (else 0)"},
       {"--initial", "VAR=VALUE", true, "initial value of an unrecorded state"},
       {"--sigma", "VAR=VALUE", true, "noise level of a column (default: the column's RMS)"},
       {"--range", "NAME=LO:HI", true, "bounds of a parameter, search box of the global stage"},
       {"--global", "", false, "a global stage first (NLopt CRS2 over start/10 .. start*10)"},
       {"--global-method", "crs|direct|isres|mlsl", false, "the global algorithm (default crs)"},
       {"--global-evaluations", "N", false, "budget of the global stage (default 400)"},
       {"--seed", "N", false, "NLopt's random seed for the global stage (default 1)"},
       {"--local", "slsqp|lbfgs|mma|bobyqa|neldermead|lm", false,
        "local method: Levenberg-Marquardt (default) or NLopt's"},
       {"--no-polish", "", false, "no Gauss-Newton steps after a local NLopt stage"},
       {"--max-evaluations", "N", false, "evaluation limit of the local stage (default 200)"},
       {"--out", "FITTED.toml", false, "write a copy of the case with the fitted values"},
       {"--json", "FILE", false, "write the fit as JSON"},
       {"--csv", "FILE", false, "write the fitted model at the data's times (scripts/plot_fit)"}});
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  return options;
}

std::vector<OptionSpec> basins_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--grid", "NAME=FROM:TO:COUNT", true,
        "a parameter's grid, COUNT values from FROM to TO (NAME=VALUE: one value); once or twice"},
       {"--starts", "N", false, "random starts per grid point (default 100)"},
       {"--angles", "MIN:MAX", false,
        "the pendula's start angles, uniform in [MIN, MAX] rad (default -0.6:0.6)"},
       {"--initial", "VAR=VALUE", true,
        "a state value every start shares (x, vx, ...: the platform moving; default at rest)"},
       {"--seed", "N", false, "seed of the starts (default 1): task i draws from seed and i alone"},
       {"--t-end", "SECONDS", false, "length of each simulation (default 100)"},
       {"--dt", "SECONDS", false, "sampling interval of the classifier (default 0.01)"},
       {"--window", "SECONDS", false, "the end of a run its class is judged on (default 10)"},
       {"--phase-tolerance", "RAD", false,
        "in or anti-phase: within this of 0 or pi; also time to sync (default 0.1)"},
       {"--lock-tolerance", "RAD", false,
        "locked: each phase difference within this of its mean over the window (default 0.1)"},
       {"--threads", "N", false,
        "simulations run side by side (default: one per core; under mpirun one per rank)"},
       {"--out", "DIR", false, "where the files go (default out/basins)"},
       {"--resume", "", false, "continue the journal in DIR: its runs are not computed again"},
       {"--quiet", "", false, "no progress line on a terminal"},
       {"--confirm", "", false,
        "confirm each locked end by Newton to a periodic orbit (its period and stability)"},
       {"--early-stop", "", false,
        "stop a run once it is certified to converge to a stable orbit reached from the case's "
        "starts; the runs then integrate with ERK at rtol 1e-6 unless --method or --rtol say "
        "otherwise"},
       accuracy_option()});
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  return options;
}

std::vector<OptionSpec> map_options() {
  return {{"--out", "DIR", false, "where the JSON and CSV files go (default out/figures)"},
          {"--jobs", "N", false, "orbits computed side by side (default 2)"},
          {"--quiet", "", false, "no progress lines"},
          accuracy_option()};
}

std::vector<OptionSpec> sweep_options() {
  auto options = case_options();
  options.insert(
      options.end(),
      {{"--start", "NAME", false,
        "named start of the case (required for a metronome case file; an equation case file's "
        "default: its [states])"},
       {"--param", "P", false,
        "each branch's parameter (without it and --data: an orbit at each value)"},
       {"--from", "A", false, "each branch's first value (required with --param)"},
       {"--to", "B", false, "each branch's last value (required with --param)"},
       {"--at", "V", false, "start each branch at V instead and continue both ways"},
       {"--over", "NAME=FROM:TO:COUNT", false,
        "the second parameter's grid: a branch (or an orbit) at each of its COUNT values", true},
       {"--initial", "VAR=VALUE", true, "initial state value (on top of --start)"},
       {"--data", "FILE.csv", false,
        "a fit to this recording at each value (the swept parameter held there), as fit's"},
       {"--free", "NAME[,NAME...]", true, "with --data: the parameters fitted"},
       {"--free-initial", "VAR[,VAR...]", true, "with --data: initial values fitted too"},
       {"--threads", "N", false,
        "tasks run side by side (default: one per core; under mpirun one per rank)"},
       {"--out", "DIR", false, "where the files go (default out/sweep)"},
       {"--resume", "", false, "continue the journal in DIR: its tasks are not computed again"},
       {"--quiet", "", false, "no progress line on a terminal"},
       accuracy_option()});
  const auto steps = branch_step_options();
  options.insert(options.end(), steps.begin(), steps.end());
  const auto integrator = integrator_options();
  options.insert(options.end(), integrator.begin(), integrator.end());
  return options;
}

std::vector<OptionSpec> bench_options() {
  return {{"--out", "DIR", false, "where bench.csv and bench.md go (default out/bench)"},
          {"--quick", "", false, "fewer tolerances (for a smoke run)"},
          {"--quiet", "", false, "no progress lines on a terminal"},
          {"--sections", "LIST", false,
           "which parts, e.g. abc (default abcdefghijkl): (a)-(c) error against run time, "
           "(d) cost of a continuation point, (e) cost against the number of metronomes, "
           "(f) the anti-phase k-branch per accuracy preset and integrator, with AUTO-07p's "
           "measured points, (g) identical metronomes in phase, reduced and whole, (h) equation "
           "case files, generated against hand-written, and their compile time, (i) the Fig. 8 "
           "study from its file, wall time, (j) the integrator chosen by the measured stiffness "
           "against each forced, (k) basin runs stopped early against full-length ones, (l) the "
           "paper's impulsive escapement (hybrid orbits) against the smoothed one at equal "
           "error"}};
}

std::vector<std::string> commands() {
  return {"simulate", "orbit",  "continue", "curve", "map",  "equilibria",
          "study",    "basins", "sweep",    "fit",   "bench"};
}

CommandOptions command_options(const std::string& command) {
  if (command == "simulate") return {{"CASE"}, simulate_options()};
  if (command == "orbit") return {{"CASE"}, orbit_options()};
  if (command == "continue") return {{"CASE"}, continue_options()};
  if (command == "curve") return {{"CASE"}, curve_options()};
  if (command == "map") return {{"MAP"}, map_options()};
  if (command == "equilibria") return {{"CASE"}, equilibria_options()};
  if (command == "study") return {{"STUDY"}, study_options()};
  if (command == "basins") return {{"CASE|STUDY.toml"}, basins_options()};
  if (command == "sweep") return {{"CASE"}, sweep_options()};
  if (command == "fit") return {{"CASE"}, fit_options()};
  if (command == "bench") return {{}, bench_options()};
  throw InputError("unknown command '" + command + "'");
}

}  // namespace sympathy::app
