#include "cases/cli/branch_run.hpp"

#include <memory>

#include "sympathy/cases/metronome_describer.hpp"
#include "sympathy/continuation/branch_output.hpp"

namespace sympathy::cli {

Branch run_branch(const LoadedCase& c, const MetronomeModel& model, const BranchRequest& request,
                  const std::atomic<bool>* stop) {
  const StartSpec& start = c.file.start(request.start);
  BranchProblem problem;
  problem.parameter = model.parameter_index(request.parameter);
  problem.values = model.default_parameters();
  problem.from = request.from;
  problem.to = request.to;
  problem.at = request.at;
  problem.start_state = c.file.initial_state(&start, request.initial);
  problem.subspace = c.file.invariant_subspace(start, model);
  problem.start_name = start.name;
  // The engine's own check of the problem, before any work ("at 3: expected a value between
  // from and to"), in the command line's names.
  if (const std::string wrong = problem.problem_with(model); !wrong.empty())
    throw InputError("--" + wrong);

  const MetronomeDescriber describer(model);
  std::unique_ptr<BranchCsvWriter> csv;
  if (!request.csv_path.empty())
    csv = std::make_unique<BranchCsvWriter>(request.csv_path, model, request.parameter, &describer);
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint& p) {
    if (csv) csv->write(p);
    if (request.progress)
      std::fprintf(request.progress,
                   "  [%4d] %s = %-14.9g T = %.9f s  %-8s max|mu| %.6f  ds %.2g (%d it)\n", p.index,
                   request.parameter.c_str(), p.parameter, p.orbit.period,
                   to_string(p.orbit.floquet.stability).c_str(), p.orbit.floquet.max_modulus,
                   p.step, p.iterations);
    if (request.progress && request.verbose) {
      std::fprintf(request.progress, "         multipliers");
      for (const auto& m : p.orbit.floquet.multipliers)
        std::fprintf(request.progress, " %.6f%+.6fi", m.value.real(), m.value.imag());
      std::fprintf(request.progress, "; trivial |mu - 1| %.1e, residual %.1e\n",
                   p.orbit.floquet.trivial_error, p.orbit.residual);
    }
  };
  std::unique_ptr<EventCsvWriter> events;
  if (!request.events_path.empty())
    events = std::make_unique<EventCsvWriter>(request.events_path, request.parameter);
  callbacks.on_event = [&](const Bifurcation& e) {
    if (events) events->write(e);
    if (request.progress)
      std::fprintf(request.progress, "  >> %s at %s = %.10g (bracket %.1e)%s%s\n",
                   to_string(e.type).c_str(), request.parameter.c_str(), e.parameter, e.uncertainty,
                   e.note.empty() ? "" : ": ", e.note.c_str());
  };
  callbacks.stop_requested = [&] { return stop && stop->load(); };
  Branch branch = continue_branch(model, problem, request.continuation, callbacks, &describer);
  if (csv) csv->close();
  if (events) events->close();
  return branch;
}

void print_events(std::FILE* out, const Branch& branch) {
  const auto& events = branch.events;
  if (events.empty()) {
    std::fprintf(out, "  no bifurcations on this branch\n");
    return;
  }
  std::fprintf(out, "  %-4s %-20s %-10s %-14s %-28s %s\n", "type", branch.parameter_name.c_str(),
               "bracket", "period (s)", "crossing multiplier", "note");
  for (const auto& e : events) {
    const std::complex<double> crossing = e.crossing;
    char mu[64];
    std::snprintf(mu, sizeof mu, "%.8f%+.8fi", crossing.real(), crossing.imag());
    std::string note = e.note;
    if (e.multiplicity > 1 && note.empty()) note = "multiplicity " + std::to_string(e.multiplicity);
    if (e.symmetry == SymmetryKind::Breaking && !branch.points.empty())
      note = "breaks " + branch.points.front().orbit.subspace.description() +
             (note.empty() ? "" : "; " + note);
    std::fprintf(out, "  %-4s %-20.12g %-10.1e %-14.10f %-28s %s\n",
                 (to_string(e.type) + (e.trusted() ? "" : "?")).c_str(), e.parameter, e.uncertainty,
                 e.period, mu, note.c_str());
  }
}

nlohmann::json branch_json(const Branch& branch, const BranchRequest& request,
                           const MetronomeModel& model) {
  const MetronomeDescriber describer(model);
  nlohmann::json j = sympathy::branch_json(branch, &describer);
  j["start"] = request.start;
  j["from"] = request.from;
  j["to"] = request.to;
  if (request.at) j["at"] = *request.at;
  return j;
}

}  // namespace sympathy::cli
