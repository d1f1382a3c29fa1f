// sympathy sweep as a request (sweep_run.hpp).
#include "cases/app/sweep_run.hpp"

#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "cases/app/fit_run.hpp"
#include "cases/app/requests.hpp"

#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

namespace {

// A located event in a journal field: TYPE:VALUE:UNCERTAINTY:TRUSTED, events joined by ';'.
std::string events_field(const Branch& b) {
  std::string s;
  for (const auto& e : b.events) {
    if (!s.empty()) s += ";";
    s += to_string(e.type) + ":" + format_double(e.parameter) + ":" + format_double(e.uncertainty) +
         ":" + (e.trusted() ? "1" : "0");
  }
  return s;
}

std::vector<std::vector<std::string>> split_events(const std::string& field) {
  std::vector<std::vector<std::string>> events;
  std::stringstream all(field);
  for (std::string one; std::getline(all, one, ';');) {
    std::vector<std::string> parts;
    std::stringstream s(one);
    for (std::string p; std::getline(s, p, ':');) parts.push_back(p);
    if (parts.size() == 4) events.push_back(parts);
  }
  return events;
}

}  // namespace

Sweep prepare_sweep(const Arguments& args, int ranks) {
  Sweep w;
  w.c = std::make_unique<LoadedSystem>(load_system(args));
  w.c->require_orbits();
  if (args.has("--param") && args.has("--data"))
    throw InputError(
        "--data: a fit at each value, given with --param (a branch at each value); "
        "expected one or the other");
  w.job = args.has("--param")  ? Sweep::Job::Branches
          : args.has("--data") ? Sweep::Job::Fits
                               : Sweep::Job::Orbits;
  if (w.job != Sweep::Job::Branches) {
    for (const char* option : {"--from", "--to", "--at", "--step", "--max-step", "--max-points"})
      if (args.has(option))
        throw InputError(std::string(option) +
                         ": a branch's option, given without --param (a sweep of orbits or "
                         "fits); expected --param P too, for a branch at each value");
  } else {
    w.window = parameter_window(args, *w.c);
  }
  if (w.job != Sweep::Job::Fits)
    for (const char* option : {"--free", "--free-initial"})
      if (args.has(option))
        throw InputError(std::string(option) +
                         ": a fit's option, given without --data; expected "
                         "--data FILE.csv too, for a fit at each value");
  w.over = parse_grid(*args.value("--over"), "--over");
  w.c->require_parameter("--over", w.over.parameter);
  if (w.job == Sweep::Job::Branches && w.over.parameter == w.window.parameter)
    throw InputError("--over " + w.over.parameter + ": expected a parameter other than --param");
  if (w.over.count < 1)
    throw InputError("--over " + *args.value("--over") + ": an empty grid; expected COUNT >= 1");
  w.values = w.over.values();
  w.c->check_range(w.over.parameter, {{"--over (from)", w.over.from}, {"--over (to)", w.over.to}});
  if (w.job == Sweep::Job::Branches) w.c->check_range(w.window.parameter, w.window.ends());
  if (!w.c->equations() && !args.has("--start")) throw InputError("--start is required");
  w.start = args.text("--start", "");
  const BranchSource start = w.c->source(w.start, args.assignments("--initial"));  // checked
  if (w.job == Sweep::Job::Fits) {
    w.fit.data = *args.value("--data");
    w.fit.free = names(args, "--free");
    w.fit.free_initial = names(args, "--free-initial");
    for (const auto& name : w.fit.free)
      if (name == w.over.parameter)
        throw InputError("--free " + name +
                         ": the swept parameter (--over), held at each value; "
                         "expected another");
    w.fit_options.flow = flow_options(args, w.fit_options.flow);
    // Once, before any work: the recording read, the names and the sample count checked; the
    // unrecorded states from the start.
    FitModel model = w.c->fit_model();
    model.initial = start.start_state;
    model.initial_source = w.start.empty() ? "start" : "--start " + w.start;
    w.prepared = prepare_fit(std::move(model), w.fit);
  }
  BranchRequest& r = w.request;
  r.start = w.start;
  r.parameter = w.window.parameter;
  r.from = w.window.from;
  r.to = w.window.to;
  r.at = w.window.at;
  r.initial = args.assignments("--initial");
  r.progress = nullptr;
  r.continuation = branch_continuation(args, w.c->system());
  check_options(r.continuation.validate(), "");
  w.run.threads = args.integer("--threads", 0);
  if (args.has("--threads") && w.run.threads < 1)
    throw InputError("--threads: expected a positive number of threads");
  if (ranks > 1 && static_cast<std::size_t>(ranks - 1) > w.values.size())
    throw InputError("mpirun -np " + std::to_string(ranks) + ": " + std::to_string(ranks - 1) +
                     " workers for " + std::to_string(w.values.size()) +
                     " tasks; expected at most " + std::to_string(w.values.size() + 1) +
                     " ranks (one manager)");
  w.out = args.text("--out", "out/sweep");
  w.journal_path = w.out + "/sweep_journal.csv";
  w.table_path = w.out + (w.job == Sweep::Job::Orbits ? "/sweep_orbits.csv"
                          : w.job == Sweep::Job::Fits ? "/sweep_fits.csv"
                                                      : "/sweep_events.csv");
  w.json_path = w.out + "/sweep.json";
  check_distinct_outputs(
      {{"journal", w.journal_path}, {"table", w.table_path}, {"json", w.json_path}},
      w.job == Sweep::Job::Fits ? with(w.c->inputs(), {"recording (--data)", w.fit.data})
                                : w.c->inputs());
  w.record = study_record(args,
                          w.job == Sweep::Job::Fits
                              ? with(w.c->inputs(), {"recording (--data)", w.fit.data})
                              : w.c->inputs(),
                          {"--threads", "--out", "--resume"});
  return w;
}

namespace {

// The journal's columns: the second parameter's value, then a branch's points, stop and events
// (events_field), or an orbit's convergence, period, stability, largest multiplier but the
// trivial one, trivial-multiplier error and residual.
TaskJournal::Row header(const Sweep& w) {
  if (w.job == Sweep::Job::Orbits)
    return {w.over.parameter, "converged",     "period",  "stability",
            "max_modulus",    "trivial_error", "residual"};
  if (w.job == Sweep::Job::Fits) {
    TaskJournal::Row h{w.over.parameter, "converged", "rss"};
    for (const auto& name : w.fit.free) h.push_back(name);
    for (const auto& name : w.fit.free_initial) h.push_back(name + "(0)");
    return h;
  }
  return {w.over.parameter, "points", "stop", "events"};
}

}  // namespace

void open_sweep_outputs(Sweep& w, bool resume) {
  if (!resume && std::filesystem::exists(w.journal_path))
    throw InputError("--out " + w.out + ": " + w.journal_path +
                     " is the journal of an earlier run; expected --resume to continue it, or "
                     "another --out (or remove the file)");
  std::filesystem::create_directories(w.out);
  for (const auto& p : {w.journal_path, w.table_path, w.json_path}) check_writable(p, "--out");
  check_or_write_study_record(w.journal_path, w.record,
                              resume && std::filesystem::exists(w.journal_path));
  w.journal = std::make_unique<TaskJournal>(w.journal_path, header(w), w.values.size(), resume);
  for (const auto& [index, row] : w.journal->rows())
    if (row[0] != format_double(w.values[index]))
      throw InputError(w.journal_path + ": task " + std::to_string(index) + " is at " +
                       w.over.parameter + " = " + row[0] + "; this sweep's is at " +
                       format_double(w.values[index]) + " (expected a journal of the same grid)");
}

namespace {

// The branches' events: sweep_events.csv, and the JSON's list.
nlohmann::json branches_json(const Sweep& w) {
  CsvWriter csv(w.table_path,
                {w.over.parameter, "type", w.window.parameter, "uncertainty", "trusted"});
  nlohmann::json branches = nlohmann::json::array();
  for (const auto& [index, row] : w.journal->rows()) {
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : split_events(row[3])) {
      csv.row(std::vector<std::string>{row[0], e[0], e[1], e[2], e[3]});
      events.push_back({{"type", e[0]},
                        {"value", std::stod(e[1])},
                        {"uncertainty", std::stod(e[2])},
                        {"trusted", e[3] == "1"}});
    }
    branches.push_back({{"task", index},
                        {"value", std::stod(row[0])},
                        {"points", std::stoi(row[1])},
                        {"stop", row[2]},
                        {"events", events}});
  }
  csv.close();
  return branches;
}

// The orbits: sweep_orbits.csv (the journal's rows in task order), and the JSON's list.
nlohmann::json orbits_json(const Sweep& w) {
  CsvWriter csv(w.table_path, header(w));
  nlohmann::json orbits = nlohmann::json::array();
  for (const auto& [index, row] : w.journal->rows()) {
    csv.row(row);
    orbits.push_back({{"task", index},
                      {"value", std::stod(row[0])},
                      {"converged", row[1] == "1"},
                      {"period", std::stod(row[2])},
                      {"stability", row[3]},
                      {"max_modulus", std::stod(row[4])},
                      {"trivial_error", std::stod(row[5])},
                      {"residual", std::stod(row[6])}});
  }
  csv.close();
  return orbits;
}

// The fits: sweep_fits.csv (the journal's rows in task order), and the JSON's list.
nlohmann::json fits_json(const Sweep& w) {
  const TaskJournal::Row names = header(w);
  CsvWriter csv(w.table_path, names);
  nlohmann::json fits = nlohmann::json::array();
  for (const auto& [index, row] : w.journal->rows()) {
    csv.row(row);
    nlohmann::json values = nlohmann::json::object();
    for (std::size_t k = 3; k < row.size(); ++k) values[names[k]] = std::stod(row[k]);
    fits.push_back({{"task", index},
                    {"value", std::stod(row[0])},
                    {"converged", row[1] == "1"},
                    {"rss", std::stod(row[2])},
                    {"values", values}});
  }
  csv.close();
  return fits;
}

}  // namespace

void write_sweep(const Sweep& w) {
  nlohmann::json j;
  j["case"] = w.c->path();
  j["params_set"] = w.c->params();
  j["start"] = w.start;
  if (w.job == Sweep::Job::Branches)
    j["parameter"] = {{"name", w.window.parameter}, {"from", w.window.from}, {"to", w.window.to}};
  if (w.job == Sweep::Job::Fits) j["data"] = w.fit.data;
  j["over"] = {{"name", w.over.parameter},
               {"from", w.over.from},
               {"to", w.over.to},
               {"count", w.over.count}};
  j["complete"] = w.journal->rows().size() == w.values.size();
  const std::string kind = sweep_unit(w);
  j[kind] = w.job == Sweep::Job::Orbits ? orbits_json(w)
            : w.job == Sweep::Job::Fits ? fits_json(w)
                                        : branches_json(w);
  write_file_atomically(w.json_path, j.dump(1) + "\n");
}

std::string sweep_unit(const Sweep& w) {
  return w.job == Sweep::Job::Orbits ? "orbits" : w.job == Sweep::Job::Fits ? "fits" : "branches";
}

std::function<std::optional<TaskRow>(std::size_t)> sweep_tasks(const Sweep& w,
                                                               const std::atomic<bool>* stop) {
  BranchSource base = w.c->source(w.start, w.request.initial);
  return [&w, base = std::move(base), stop](std::size_t index) -> std::optional<TaskRow> {
    const OdeSystem& system = w.c->system();
    const int over = system.parameter_index(w.over.parameter);
    BranchSource source = base;
    source.values = system.with_parameter(base.values, over, w.values[index]);
    if (w.job == Sweep::Job::Fits) {
      // The prepared problem with the swept value held.
      TrajectoryFitProblem problem = w.prepared->problem;
      problem.parameter_values = source.values;
      const TrajectoryFitResult r = fit_trajectory(*w.prepared->model, problem, w.fit_options);
      TaskRow row{format_double(w.values[index]), r.converged ? "1" : "0", format_double(r.rss)};
      for (int k = 0; k < r.values.size(); ++k) row.push_back(format_double(r.values[k]));
      return row;
    }
    if (w.job == Sweep::Job::Orbits) {
      const PeriodicOrbit o = find_periodic_orbit(system, source.values, source.start_state,
                                                  source.subspace, w.request.continuation.orbit);
      const auto& f = o.floquet;
      return TaskRow{format_double(w.values[index]), o.converged() ? "1" : "0",
                     format_double(o.period),        to_string(f.stability),
                     format_double(f.max_modulus),   format_double(f.trivial_error),
                     format_double(o.residual)};
    }
    const Branch b = run_branch(source, w.request, stop);
    if (b.stop == StopReason::Interrupted) return std::nullopt;
    return TaskRow{format_double(w.values[index]), std::to_string(b.points.size()),
                   to_string(b.stop), events_field(b)};
  };
}

JournaledOutcome run_sweep_here(const Arguments& args, const std::atomic<bool>* stop,
                                const std::function<void(std::size_t, std::size_t)>& on_recorded) {
  Sweep w = prepare_sweep(args, 1);
  open_sweep_outputs(w, args.flag("--resume"));
  const MpiSession local;  // not under mpirun: one rank, the tasks on threads
  const auto summary = run_journaled(local, w.values.size(), w.journal.get(), sweep_tasks(w, stop),
                                     w.run, stop, [&](std::size_t done) {
                                       if (on_recorded) on_recorded(done, w.values.size());
                                     });
  w.journal->close();
  write_sweep(w);
  return {w.json_path, summary.interrupted};
}

}  // namespace sympathy::app
