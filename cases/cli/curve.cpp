// sympathy curve: the two-parameter curve of a bifurcation located on a branch (LP, BP, PD, NS),
// followed in a second parameter; the branch computed as `continue` computes it, or read from
// its JSON.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/equilibrium_curve_run.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/start_data.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"

namespace sympathy::cli {

namespace {

void print_curve_events(std::FILE* out, const BifurcationCurve& curve) {
  if (curve.events.empty()) {
    std::fprintf(out, "  none\n");
    return;
  }
  std::fprintf(out, "  %-10s %-20s %-20s %-11s %s\n", "type", curve.first_name.c_str(),
               curve.second_name.c_str(), "uncertainty", "note");
  for (const auto& e : curve.events)
    std::fprintf(out, "  %-10s %-20.12g %-20.12g %-11.1e %s%s%s\n", e.type.c_str(), e.first,
                 e.second, e.uncertainty, e.description.c_str(), e.note.empty() ? "" : "; ",
                 e.note.c_str());
}

// A curve of cycles' summary (its points, stop, codimension-two points and turns, run time), its
// JSON, and the exit code.
int finish_curve(const CurveRequest& r, const BifurcationCurve& curve, const LoadedSystem& c,
                 const Stopwatch& clock) {
  std::printf("  %zu points; stopped: %s\n", curve.points.size(), curve.stop_reason.c_str());
  std::printf("codimension-two points and turns:\n");
  print_curve_events(stdout, curve);
  std::printf("  run time %.3f s (the curve %.3f s: %d monodromies, %ld steps; noise %.1e)\n",
              clock.seconds(), curve.seconds, curve.evaluations, curve.flow.steps, curve.noise);
  if (!r.json_path.empty()) write_curve_json(r, curve, c, clock.seconds());
  return exit_code_of(curve);
}

// The fold or Hopf curve of equilibria from an event of --parent EQUILIBRIA.json.
int run_equilibrium_curve(const Arguments& args, const LoadedSystem& c, const Stopwatch& clock) {
  const EquilibriumCurveRequest r = equilibrium_curve_request(args, c);
  const OdeSystem& system = c.system();
  const std::string first = r.parent.parameter_name;
  const std::string second = system.parameter_names()[r.second];
  if (r.codimension_two)
    std::printf(
        "sympathy curve %s  params %s  the %s curve through %s of %s, in %s and %s (%g to "
        "%g)\n",
        c.path().c_str(), c.params().empty() ? "(none)" : c.params().c_str(),
        r.codimension_two->type == "HH" || (r.codimension_two->on == EquilibriumEventType::Fold &&
                                            r.codimension_two->type != "CP")
            ? "Hopf"
            : "fold",
        r.event_name.c_str(), r.parent_path.c_str(), first.c_str(), second.c_str(),
        r.options.second_lower, r.options.second_upper);
  else
    std::printf("sympathy curve %s  params %s  %s of the equilibria in %s (%s) in %s (%g to %g)\n",
                c.path().c_str(), c.params().empty() ? "(none)" : c.params().c_str(),
                r.event_name.c_str(), first.c_str(), r.parent_path.c_str(), second.c_str(),
                r.options.second_lower, r.options.second_upper);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const bool quiet = args.flag("--quiet");
  ProgressLine progress(quiet);
  std::FILE* log = progress.log();
  int points = 0;
  EquilibriumCurveCallbacks callbacks;
  callbacks.on_point = [&](const EquilibriumCurvePoint& p) {
    ++points;
    if (!quiet) {
      std::fprintf(log, "  [%4d] %s = %-14.9g %s = %-14.9g", p.index, first.c_str(), p.first,
                   second.c_str(), p.second);
      if (std::isfinite(p.kappa))
        std::fprintf(log, "  %s %.6g", p.neutral_saddle ? "k^2" : "omega^2", std::abs(p.kappa));
      std::fprintf(log, "  (%d it)\n", p.iterations);
    }
    progress.show("curve " + r.event_name + ": " + first + " = " + format_number(p.first) + ", " +
                  second + " = " + format_number(p.second) + ", " + std::to_string(points) +
                  " points, " + duration_text(clock.seconds()));
  };
  callbacks.on_event = [&](const EquilibriumCurveEvent& e) {
    if (!quiet)
      std::fprintf(log, "  >> %s at %s = %.10g, %s = %.10g\n", e.type.c_str(), first.c_str(),
                   e.first, second.c_str(), e.second);
  };
  callbacks.stop_requested = [] { return interrupt_flag()->load(); };
  const EquilibriumCurve curve = run_equilibrium_curve(r, system, callbacks);
  progress.clear();
  if (!curve.started()) {
    std::printf("  %s\n  run time %.3f s\n", curve.stop_reason.c_str(), clock.seconds());
    return 4;
  }
  int saddles = 0;
  for (const auto& p : curve.points) saddles += p.neutral_saddle;
  std::printf("  %zu points; stopped: %s\n", curve.points.size(), curve.stop_reason.c_str());
  if (saddles)
    std::printf("  %d of them neutral saddles (real eigenvalues +-k, not Hopf points)\n", saddles);
  std::printf("codimension-two points:\n");
  if (curve.events.empty())
    std::printf("  none\n");
  else
    std::printf("  %-4s %-20s %-20s %-11s %s\n", "type", first.c_str(), second.c_str(),
                "uncertainty", "note");
  for (const auto& e : curve.events)
    std::printf("  %-4s %-20.12g %-20.12g %-11.1e %s%s%s\n",
                (e.type + (e.located ? "" : "?")).c_str(), e.first, e.second, e.uncertainty,
                e.description.c_str(), e.note.empty() ? "" : "; ", e.note.c_str());
  std::printf("  run time %.3f s\n", clock.seconds());
  if (!r.json_path.empty()) write_equilibrium_curve_json(r, curve, c, clock.seconds());
  return exit_code_of(curve);
}

// The fold of cycles born at a generalized Hopf point of --parent HOPF_CURVE.json.
int run_generalized_hopf_fold(const Arguments& args, const LoadedSystem& c, const CurveRequest& r,
                              const Stopwatch& clock) {
  const std::string& first = r.branch.parameter;
  const std::string& second = r.second;
  std::printf(
      "sympathy curve %s  params %s  the fold of cycles born at %s of the Hopf curve in %s "
      "in %s (%g to %g) and %s (%g to %g)\n",
      c.path().c_str(), c.params().empty() ? "(none)" : c.params().c_str(), r.event.text.c_str(),
      r.branch.parent_path.c_str(), first.c_str(), r.options.first_lower, r.options.first_upper,
      second.c_str(), r.options.second_lower, r.options.second_upper);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const bool quiet = args.flag("--quiet");
  ProgressLine progress(quiet);
  int points = 0;
  CurveCallbacks callbacks;
  callbacks.on_point = [&](const CurvePoint& p) {
    progress.show("fold of cycles from " + r.event.text + ": " + first + " = " +
                  format_number(p.first) + ", " + second + " = " + format_number(p.second) + ", " +
                  std::to_string(++points) + " points, " + duration_text(clock.seconds()));
  };
  callbacks.stop_requested = [] { return interrupt_flag()->load(); };
  GeneralizedHopfFold start;
  const BifurcationCurve curve =
      follow_generalized_hopf_fold(r, c.system(), callbacks, &c.describer(), start);
  progress.clear();
  const GeneralizedHopfPoint& gh = *r.generalized_hopf;
  std::printf("  %s at %s = %.10g, %s = %.10g: l2 = %.6g, a fold of cycles where l1 %s 0\n",
              r.event.text.c_str(), first.c_str(), c.system().parameter(gh.at.values, gh.at.first),
              second.c_str(), c.system().parameter(gh.at.values, gh.at.second), gh.l2,
              gh.l2 < 0 ? ">" : "<");
  std::printf(
      "  the family born at the Hopf point %s = %.10g, %s = %.10g (l1 = %.6g): %zu points "
      "to its fold at %s = %.10g (T = %.10g)\n",
      first.c_str(), start.hopf.parameter, second.c_str(),
      c.system().parameter(start.hopf.values, gh.at.second), *start.hopf.lyapunov,
      start.family.points.size(), first.c_str(), start.fold.parameter, start.fold.period);
  return finish_curve(r, curve, c, clock);
}

}  // namespace

int run_curve(const std::vector<std::string>& argv) {
  Arguments args("curve", argv, curve_options(), {"CASE"});
  Stopwatch clock;
  const LoadedSystem c = load_system(args);
  if (wants_equilibrium_curve(args)) return run_equilibrium_curve(args, c, clock);
  const CurveRequest r = curve_request(args, c);
  if (r.generalized_hopf) return run_generalized_hopf_fold(args, c, r, clock);
  const BranchRequest& request = r.branch;
  const EventName& name = r.event;
  const std::string& second = r.second;
  const CurveOptions& curve_options = r.options;
  const BranchSource source = c.source(request.start, request.initial, request.start_data);

  std::printf(
      "sympathy curve %s  params %s  start %s  %s of the %s-branch (%g to %g) in %s "
      "(%g to %g)\n",
      c.path().c_str(), c.params().empty() ? "(none)" : c.params().c_str(),
      request.start_data      ? describe_start_data(*request.start_data).c_str()
      : request.start.empty() ? "(the file's [states])"
                              : request.start.c_str(),
      name.text.c_str(), request.parameter.c_str(), request.from, request.to, second.c_str(),
      curve_options.second_lower, curve_options.second_upper);
  if (c.equations()) std::printf("  %s\n", c.build_note().c_str());
  std::fflush(stdout);
  const OdeSystem& model = c.system();
  const Branch parent = curve_branch(r, c, source, interrupt_flag());
  if (!parent.started()) {
    std::printf("  the branch: %s\n  run time %.3f s\n", parent.stop_reason.c_str(),
                clock.seconds());
    return kNumericalFailure;
  }
  if (interrupt_flag()->load()) return kInterrupted;
  const Bifurcation& event = find_event(parent, name, "--event");
  std::printf("  the branch: %zu points %s; %s at %s = %.10g\n", parent.points.size(),
              request.parent_path.empty()
                  ? ("in " + format_number(std::round(parent.seconds * 100) / 100) + " s").c_str()
                  : ("from " + request.parent_path).c_str(),
              name.text.c_str(), request.parameter.c_str(), event.parameter);
  std::fflush(stdout);

  const bool quiet = args.flag("--quiet");
  ProgressLine progress(quiet);
  std::FILE* log = progress.log();
  int points = 0;
  CurveCallbacks callbacks;
  callbacks.on_point = [&](const CurvePoint& p) {
    if (!quiet) {
      std::fprintf(log, "  [%4d] %s = %-14.9g %s = %-14.9g T = %.9f s  critical %.6f%+.6fi",
                   p.index, request.parameter.c_str(), p.first, second.c_str(), p.second, p.period,
                   p.critical.empty() ? NAN : p.critical[0].real(),
                   p.critical.empty() ? NAN : p.critical[0].imag());
      if (std::isfinite(p.rotation)) std::fprintf(log, "  rotation %.6f", p.rotation);
      std::fprintf(log, "  (%d it)\n", p.iterations);
    }
    progress.show("curve " + name.text + ": " + request.parameter + " = " + format_number(p.first) +
                  ", " + second + " = " + format_number(p.second) + ", " +
                  std::to_string(++points) + " points, " + duration_text(clock.seconds()));
  };
  callbacks.on_event = [&](const CurveEvent& e) {
    if (!quiet)
      std::fprintf(log, "  >> %s at %s = %.10g, %s = %.10g\n", e.type.c_str(),
                   request.parameter.c_str(), e.first, second.c_str(), e.second);
  };
  callbacks.stop_requested = [] { return interrupt_flag()->load(); };
  const BifurcationCurve curve = follow_curve(r, model, parent, event, callbacks, &c.describer());
  progress.clear();
  return finish_curve(r, curve, c, clock);
}

}  // namespace sympathy::cli
