#include "cases/cli/branch_run.hpp"

#include <algorithm>
#include <cmath>
#include <csignal>
#include <memory>

#include "sympathy/core/csv.hpp"

namespace sympathy::cli {

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  if (g_interrupted.exchange(true)) std::_Exit(130);
}

std::vector<std::string> csv_header(const MetronomeModel& model, const std::string& parameter) {
  std::vector<std::string> h{
      "index",     parameter,        "period",      "frequency",
      "stability", "unstable_count", "max_modulus", "trivial_multiplier_error",
      "residual",  "structural",     "iterations",  "step"};
  const auto names = model.state_names();
  for (int i = 0; i < model.dimension() / 2; ++i) h.push_back("amp_" + names[i]);
  for (int i = 1; i < model.metronome_count(); ++i) h.push_back("phase_th" + std::to_string(i + 1));
  for (int i = 0; i < model.dimension(); ++i) {
    h.push_back("mu" + std::to_string(i + 1) + "_re");
    h.push_back("mu" + std::to_string(i + 1) + "_im");
  }
  // The orbit's initial state: any point can seed a new run (--initial NAME=VALUE...).
  for (const auto& n : names) h.push_back(n);
  return h;
}

std::vector<std::string> csv_row(const ContinuationPoint& p, const OrbitReport& r) {
  const auto& f = p.orbit.floquet;
  std::vector<std::string> row{std::to_string(p.index),         format_double(p.parameter),
                               format_double(p.orbit.period),   format_double(1.0 / p.orbit.period),
                               to_string(f.stability),          std::to_string(f.unstable_count),
                               format_double(f.max_modulus),    format_double(f.trivial_error),
                               format_double(p.orbit.residual), std::to_string(f.structural),
                               std::to_string(p.iterations),    format_double(p.step)};
  for (double a : r.amplitudes) row.push_back(format_double(a));
  for (double d : r.phase_differences) row.push_back(format_double(d));
  for (const auto& m : f.multipliers) {
    row.push_back(format_double(m.value.real()));
    row.push_back(format_double(m.value.imag()));
  }
  for (int i = 0; i < p.orbit.state0.size(); ++i) row.push_back(format_double(p.orbit.state0[i]));
  return row;
}

nlohmann::json multiplier_list(const FloquetAnalysis& f) {
  return multipliers_json(f);
}

}  // namespace

const std::atomic<bool>* interrupt_flag() {
  std::signal(SIGINT, on_interrupt);
  return &g_interrupted;
}

BranchResult run_branch(const LoadedCase& c, const BranchRequest& request,
                        const std::atomic<bool>* stop) {
  Stopwatch clock;
  BranchResult result;
  MetronomeModel model(c.spec);
  const int parameter = model.parameter_index(request.parameter);
  const StartSpec& start = c.file.start(request.start);
  const InvariantSubspace subspace = c.file.invariant_subspace(start, model);
  const double first = request.at ? *request.at : request.from;
  model.set_parameter(parameter, first);

  OrbitOptions orbit_options = request.continuation.orbit;
  orbit_options.transient = request.transient;
  const PeriodicOrbit orbit = find_periodic_orbit(
      model, c.file.initial_state(&start, request.initial), subspace, orbit_options);
  if (!orbit.converged()) {
    result.start_failure = "no periodic orbit from start '" + start.name + "' at " +
                           request.parameter + " = " + format_double(first) + ": " +
                           orbit.newton.reason;
    result.seconds = clock.seconds();
    return result;
  }
  result.started = true;

  ContinuationOptions options = request.continuation;
  options.lower = std::min(request.from, request.to);
  options.upper = std::max(request.from, request.to);
  if (request.at && !(*request.at > options.lower && *request.at < options.upper))
    throw InputError("--at " + format_double(*request.at) + ": expected a value between --from " +
                     "and --to");

  std::unique_ptr<CsvWriter> csv;
  if (!request.csv_path.empty())
    csv = std::make_unique<CsvWriter>(request.csv_path, csv_header(model, request.parameter));
  std::vector<std::pair<int, OrbitReport>> reports;
  int index_sign = +1;  // -1 on the backward part of a two-way run
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint& point) {
    ContinuationPoint p = point;
    p.index *= index_sign;
    OrbitReport r = describe_orbit(model, p.orbit);
    if (csv) {
      csv->row(csv_row(p, r));
      csv->flush();  // nothing computed is lost if the run stops
    }
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
    reports.emplace_back(p.index, std::move(r));
  };
  callbacks.on_event = [&](const Bifurcation& e) {
    if (request.progress)
      std::fprintf(request.progress, "  >> %s at %s = %.10g (bracket %.1e)%s%s\n",
                   to_string(e.type).c_str(), request.parameter.c_str(), e.parameter, e.uncertainty,
                   e.note.empty() ? "" : ": ", e.note.c_str());
  };
  callbacks.stop_requested = [&] { return stop && stop->load(); };

  Continuation continuation(model, parameter, options);
  const int toward = request.to >= first ? +1 : -1;
  Branch forward = continuation.run(orbit, toward, callbacks);
  Branch& branch = result.branch;
  branch.parameter_name = request.parameter;
  if (request.at && !(stop && stop->load())) {
    model.set_parameter(parameter, first);
    index_sign = -1;
    Branch backward = continuation.run(orbit, -toward, callbacks);
    for (auto& p : backward.points) p.index = -p.index;
    // The point before each event along the merged branch: -(k+1) for one between -k and -(k+1).
    for (auto& e : backward.events) e.after_point = -(e.after_point + 1);
    // Along the branch: the backward part reversed (without its copy of the start), then forward.
    for (auto it = backward.points.rbegin(); it != backward.points.rend() - 1; ++it)
      branch.points.push_back(std::move(*it));
    for (auto& e : backward.events) branch.events.push_back(std::move(e));
    branch.stop_reason = "backward: " + backward.stop_reason + "; forward: " + forward.stop_reason;
    branch.flow += backward.flow;
    branch.rejected += backward.rejected;
  } else {
    branch.stop_reason = forward.stop_reason;
  }
  for (auto& p : forward.points) branch.points.push_back(std::move(p));
  for (auto& e : forward.events) branch.events.push_back(std::move(e));
  branch.flow += forward.flow;
  branch.rejected += forward.rejected;
  // Along the branch: by the point before each event, then by arclength from it (the backward
  // part's indices are negative and its arclength runs the other way).
  std::stable_sort(branch.events.begin(), branch.events.end(), [](const auto& a, const auto& b) {
    if (a.after_point != b.after_point) return a.after_point < b.after_point;
    return a.after_point < 0 ? a.arclength > b.arclength : a.arclength < b.arclength;
  });
  for (const auto& p : branch.points)
    for (auto& [index, r] : reports)
      if (index == p.index) {
        result.reports.push_back(r);
        break;
      }
  result.seconds = clock.seconds();
  return result;
}

void print_events(std::FILE* out, const BranchResult& r, const std::string& parameter) {
  const auto& events = r.branch.events;
  if (events.empty()) {
    std::fprintf(out, "  no bifurcations on this branch\n");
    return;
  }
  std::fprintf(out, "  %-4s %-20s %-10s %-14s %-28s %s\n", "type", parameter.c_str(), "bracket",
               "period (s)", "crossing multiplier", "note");
  for (const auto& e : events) {
    const std::complex<double> crossing = e.crossing;
    char mu[64];
    std::snprintf(mu, sizeof mu, "%.8f%+.8fi", crossing.real(), crossing.imag());
    std::string note = e.note;
    if (e.multiplicity > 1 && note.empty()) note = "multiplicity " + std::to_string(e.multiplicity);
    if (!e.trusted && note.find("not trusted") == std::string::npos) note += " (not trusted)";
    std::fprintf(out, "  %-4s %-20.12g %-10.1e %-14.10f %-28s %s\n",
                 (to_string(e.type) + (e.trusted ? "" : "?")).c_str(), e.parameter, e.uncertainty,
                 e.period, mu, note.c_str());
  }
}

nlohmann::json branch_json(const BranchResult& r, const BranchRequest& request,
                           const MetronomeModel& model) {
  nlohmann::json j;
  j["parameter"] = request.parameter;
  j["start"] = request.start;
  j["from"] = request.from;
  j["to"] = request.to;
  if (request.at) j["at"] = *request.at;
  j["stop_reason"] = r.started ? r.branch.stop_reason : r.start_failure;
  j["state_names"] = model.state_names();
  nlohmann::json points = nlohmann::json::array();
  for (std::size_t i = 0; i < r.branch.points.size(); ++i) {
    const auto& p = r.branch.points[i];
    const auto& f = p.orbit.floquet;
    nlohmann::json q;
    q["index"] = p.index;
    q["value"] = p.parameter;
    q["period"] = p.orbit.period;
    q["frequency"] = 1.0 / p.orbit.period;
    q["stable"] = f.stability == Stability::Stable;
    q["stability"] = to_string(f.stability);
    q["multipliers"] = multiplier_list(f);
    q["trivial_multiplier_error"] = f.trivial_error;
    q["residual"] = p.orbit.residual;
    q["structural"] = f.structural;
    q["state0"] =
        std::vector<double>(p.orbit.state0.data(), p.orbit.state0.data() + p.orbit.state0.size());
    if (i < r.reports.size()) {
      q["amplitudes"] = r.reports[i].amplitudes;
      q["phase_differences"] = r.reports[i].phase_differences;
    }
    points.push_back(q);
  }
  j["points"] = points;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : r.branch.events) {
    events.push_back({{"type", to_string(e.type)},
                      {"name", describe(e.type)},
                      {"value", e.parameter},
                      {"uncertainty", e.uncertainty},
                      {"period", e.period},
                      {"multipliers", multiplier_list(e.floquet)},
                      {"crossing_multiplier", {e.crossing.real(), e.crossing.imag()}},
                      {"multiplicity", e.multiplicity},
                      {"located", e.located},
                      {"trusted", e.trusted},
                      {"note", e.note}});
  }
  j["events"] = events;
  j["seconds"] = r.seconds;
  j["flow"] = {{"integrations", r.branch.flow.calls},
               {"steps", r.branch.flow.steps},
               {"rhs_evaluations", r.branch.flow.rhs_evaluations},
               {"sensitivity_rhs_evaluations", r.branch.flow.variational_evaluations}};
  return j;
}

}  // namespace sympathy::cli
