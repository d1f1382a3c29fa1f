#include "cases/app/branch_run.hpp"

#include <algorithm>
#include <fstream>
#include <map>
#include <memory>

#include "cases/app/hopf_switch.hpp"
#include "cases/app/json_reader.hpp"
#include "sympathy/cases/metronome_describer.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/branch_switching.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy::app {

Branch run_branch(const LoadedCase& c, const MetronomeModel& model, const BranchRequest& request,
                  const std::atomic<bool>* stop) {
  const MetronomeDescriber describer(model);
  if (const auto& data = request.start_data)
    return run_branch(BranchSource{model, describer, model.default_parameters(), data->state0,
                                   InvariantSubspace(), "data " + data->path, data->period},
                      request, stop);
  const StartSpec& start = c.file.start(request.start);
  const BranchSource source{model,
                            describer,
                            model.default_parameters(),
                            c.file.initial_state(&start, request.initial),
                            c.file.invariant_subspace(start, model),
                            start.name,
                            std::nullopt};
  return run_branch(source, request, stop);
}

Branch run_branch(const BranchSource& source, const BranchRequest& request,
                  const std::atomic<bool>* stop) {
  const OdeSystem& model = source.system;
  const OrbitDescriber& describer = source.describer;
  BranchProblem problem;
  problem.parameter = model.parameter_index(request.parameter);
  problem.values = source.values;
  problem.from = request.from;
  problem.to = request.to;
  problem.at = request.at;
  problem.start_state = source.start_state;
  problem.subspace = source.subspace;
  problem.start_name = source.start_name;
  problem.start_period = request.period_guess ? request.period_guess : source.start_period;
  // The engine's own check of the problem, before any work ("at 3: expected a value between
  // from and to"), in the command line's names.
  if (const std::string wrong = problem.problem_with(model); !wrong.empty())
    // The problem's field `parameter` is the option --param; the others share their names.
    throw InputError(wrong.rfind("parameter ", 0) == 0 ? "--param" + wrong.substr(9)
                                                       : "--" + wrong);

  std::unique_ptr<BranchCsvWriter> csv;
  if (!request.csv_path.empty())
    csv = std::make_unique<BranchCsvWriter>(request.csv_path, model, request.parameter, &describer);
  ContinuationCallbacks callbacks;
  callbacks.on_point = [&](const ContinuationPoint& p) {
    if (csv) csv->write(p);
    if (request.on_point) request.on_point(p);
    if (request.progress)
      std::fprintf(request.progress,
                   "  [%4d] %s = %-14.9g T = %.9f s  %-10s max|mu| %.6f  ds %.2g (%d it)\n",
                   p.index, request.parameter.c_str(), p.parameter, p.orbit.period,
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
      std::fprintf(request.progress, "  >> %s at %s = %.10g (+- %.1e)%s%s\n",
                   to_string(e.type).c_str(), request.parameter.c_str(), e.parameter, e.uncertainty,
                   e.note.empty() ? "" : ": ", e.note.c_str());
  };
  callbacks.stop_requested = [&] {
    return (stop && stop->load()) || (request.stop_requested && request.stop_requested());
  };
  if (request.hopf_point) {
    // The family born at a point of a saved Hopf curve: its points described as they come.
    ContinuationCallbacks described = callbacks;
    described.on_point = [&](const ContinuationPoint& p) {
      ContinuationPoint q = p;
      q.description = describer.describe(q.orbit);
      callbacks.on_point(q);
    };
    Branch born =
        run_hopf_family(model, request, *request.hopf_point, request.hopf_point_name, described);
    for (auto& p : born.points) p.description = describer.describe(p.orbit);
    describe_events(born, model, describer, request.hopf_point->values);
    if (csv) csv->close();
    if (events) events->close();
    return born;
  }
  if (request.switch_at.empty()) {
    Branch branch = continue_branch(model, problem, request.continuation, callbacks, &describer);
    if (csv) csv->close();
    if (events) events->close();
    return branch;
  }

  if (const auto hb = parse_hopf_name(request.switch_at, "--switch-at")) {
    // The family born at a Hopf point of the equilibria: its points described as they come.
    ContinuationCallbacks described = callbacks;
    described.on_point = [&](const ContinuationPoint& p) {
      ContinuationPoint q = p;
      q.description = describer.describe(q.orbit);
      callbacks.on_point(q);
    };
    Branch born = run_hopf_branch(source, request, *hb, described);
    for (auto& p : born.points) p.description = describer.describe(p.orbit);
    describe_events(born, model, describer, source.values);
    if (csv) csv->close();
    if (events) events->close();
    return born;
  }

  // The branch asked for, with its progress only; then the one born at the named event.
  const EventName name = parse_event_name(request.switch_at, "--switch-at");
  ContinuationCallbacks parent_callbacks;
  parent_callbacks.stop_requested = callbacks.stop_requested;
  if (request.progress) {
    parent_callbacks.on_point = [&](const ContinuationPoint& p) {
      std::fprintf(request.progress, "  (parent %4d) %s = %-14.9g T = %.9f s  %s\n", p.index,
                   request.parameter.c_str(), p.parameter, p.orbit.period,
                   to_string(p.orbit.floquet.stability).c_str());
    };
    parent_callbacks.on_event = [&](const Bifurcation& e) {
      std::fprintf(request.progress, "  (parent) >> %s at %s = %.10g\n", to_string(e.type).c_str(),
                   request.parameter.c_str(), e.parameter);
    };
  }
  const Branch parent =
      request.parent_branch ? *request.parent_branch
      : request.parent_path.empty()
          ? continue_branch(model, problem, request.continuation, parent_callbacks)
          : read_branch_json(request.parent_path, model, problem.subspace);
  if (!parent.started()) return parent;
  if (parent.parameter_name != request.parameter)
    throw InputError("--parent " + request.parent_path + ": a branch in " + parent.parameter_name +
                     "; expected one in --param " + request.parameter);
  if (callbacks.stop_requested()) return parent;
  const Bifurcation& event = find_event(parent, name, "--switch-at");
  if (request.progress)
    std::fprintf(request.progress, "  switching at %s: %s = %.10g\n", name.text.c_str(),
                 request.parameter.c_str(), event.parameter);
  ContinuationCallbacks born_callbacks = callbacks;
  born_callbacks.on_point = [&](const ContinuationPoint& p) {
    ContinuationPoint q = p;
    q.description = describer.describe(q.orbit);
    callbacks.on_point(q);
  };
  ContinuationOptions window = request.continuation;
  window.lower = std::min(request.from, request.to);
  window.upper = std::max(request.from, request.to);
  Branch born;
  try {
    born = switch_branch(model, parent, event, window, born_callbacks);
  } catch (const std::runtime_error& e) {
    born.parameter_name = parent.parameter_name;
    born.parameter = parent.parameter;
    born.state_names = parent.state_names;
    born.stop = StopReason::StartFailed;
    born.stop_reason = std::string("no branch born at ") + name.text + ": " + e.what();
  }
  for (auto& p : born.points) p.description = describer.describe(p.orbit);
  describe_events(born, model, describer, source.values);
  born.flow += parent.flow;
  if (csv) csv->close();
  if (events) events->close();
  return born;
}

namespace {

Branch branch_from_json(const JsonReader& in, const OdeSystem& model,
                        const InvariantSubspace& subspace);

}  // namespace

Branch read_branch_json(const std::string& path, const OdeSystem& model,
                        const InvariantSubspace& subspace) {
  const JsonReader in(path, "a branch JSON written by sympathy continue --json");
  return in.read([&](const nlohmann::json&) { return branch_from_json(in, model, subspace); });
}

namespace {

Branch branch_from_json(const JsonReader& in, const OdeSystem& model,
                        const InvariantSubspace& subspace) {
  const nlohmann::json& j = in.root();
  const std::string& path = in.path();
  auto key = [&](const nlohmann::json& x, const std::string& name,
                 const std::string& where) -> const nlohmann::json& {
    return in.key(x, name, where);
  };
  auto vector_of = [&](const nlohmann::json& x, const std::string& where, int size = -1) {
    return in.numbers(x, where, size);
  };
  Branch b;
  const auto& name = key(j, "parameter", path);
  if (!name.is_string()) throw InputError(path + ": key 'parameter': expected a name");
  b.parameter_name = name.get<std::string>();
  try {
    b.parameter = model.parameter_index(b.parameter_name);
  } catch (const std::invalid_argument& e) {
    throw InputError(path + ": key 'parameter': " + e.what());
  }
  b.start_values = vector_of(key(j, "parameter_values", path), path + ": key 'parameter_values'",
                             model.parameter_values_size());
  b.state_names = model.state_names();
  const int n = model.dimension();
  const auto& points = key(j, "points", path);
  if (!points.is_array()) throw InputError(path + ": key 'points': expected a list");
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::string where = path + ": points[" + std::to_string(i) + "]";
    ContinuationPoint p;
    p.index = key(points[i], "index", where).get<int>();
    p.parameter = key(points[i], "value", where).get<double>();
    p.orbit.state0 = vector_of(key(points[i], "state0", where), where + ".state0", n);
    p.orbit.period = key(points[i], "period", where).get<double>();
    p.orbit.parameters = model.with_parameter(b.start_values, b.parameter, p.parameter);
    if (points[i].contains("segments")) p.orbit.segments = points[i]["segments"].get<int>();
    p.orbit.family_dimension = key(points[i], "structural", where).get<int>();
    p.orbit.subspace = subspace;
    b.points.push_back(std::move(p));
  }
  const auto& events = key(j, "events", path);
  if (!events.is_array()) throw InputError(path + ": key 'events': expected a list");
  for (std::size_t i = 0; i < events.size(); ++i) {
    const std::string where = path + ": events[" + std::to_string(i) + "]";
    const auto& e = events[i];
    Bifurcation ev;
    const std::string type = key(e, "type", where).get<std::string>();
    const std::vector<std::pair<std::string, BifurcationType>> types{
        {"LP", BifurcationType::Fold},
        {"BP", BifurcationType::BranchPoint},
        {"PD", BifurcationType::PeriodDoubling},
        {"NS", BifurcationType::NeimarkSacker},
        {"UZ", BifurcationType::UserPoint}};
    const auto t =
        std::find_if(types.begin(), types.end(), [&](const auto& x) { return x.first == type; });
    if (t == types.end()) throw InputError(where + ".type: expected LP, BP, PD, NS or UZ");
    ev.type = t->second;
    ev.parameter = key(e, "value", where).get<double>();
    ev.period = key(e, "period", where).get<double>();
    ev.location = key(e, "located", where).get<bool>() ? LocationOutcome::Located
                                                       : LocationOutcome::NotNarrowed;
    const std::string symmetry = key(e, "symmetry", where).get<std::string>();
    ev.symmetry = symmetry == "breaks"  ? SymmetryKind::Breaking
                  : symmetry == "keeps" ? SymmetryKind::Keeping
                                        : SymmetryKind::Unlabelled;
    ev.state0 = vector_of(key(e, "state0", where), where + ".state0", n);
    ev.unknowns = vector_of(key(e, "unknowns", where), where + ".unknowns");
    ev.tangent = vector_of(key(e, "tangent", where), where + ".tangent",
                           static_cast<int>(ev.unknowns.size()) + 1);
    ev.after_point = key(e, "after_point", where).get<int>();
    b.events.push_back(std::move(ev));
  }
  return b;
}

}  // namespace

const Bifurcation& find_event(const Branch& branch, const EventName& name,
                              const std::string& option) {
  int seen = 0;
  std::string list;
  std::map<std::string, int> counts;
  for (const auto& e : branch.events) {
    const std::string type = to_string(e.type);
    list += (list.empty() ? "" : ", ") + type + std::to_string(++counts[type]) + " at " +
            format_double(e.parameter);
    if (e.type == name.type && ++seen == name.ordinal) return e;
  }
  throw InputError(option + " " + name.text + ": the branch has no such event; it has " +
                   (list.empty() ? std::string("none") : list));
}

nlohmann::json branch_json(const Branch& branch, const BranchRequest& request,
                           const OrbitDescriber& describer) {
  nlohmann::json j = sympathy::branch_json(branch, &describer);
  j["start"] = request.start;
  if (request.start_data) j["start_data"] = request.start_data->path;
  j["from"] = request.from;
  j["to"] = request.to;
  if (request.at) j["at"] = *request.at;
  return j;
}

}  // namespace sympathy::app
