#include "cases/app/study_run.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "cases/app/case_arguments.hpp"
#include "cases/app/hopf_switch.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/start_data.hpp"
#include "sympathy/continuation/branch_output.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/option_check.hpp"
#include "sympathy/core/output_file.hpp"

namespace sympathy::app {

StudyRun study_run(const Arguments& args, const MpiSession* mpi) {
  StudyRun run;
  run.mpi = mpi;
  run.study = load_study(args.positional(0));
  Study& study = run.study;
  run.out = args.text("--out", "out/figures");
  const std::string& out = run.out;
  run.jobs = args.integer("--jobs", 2);
  run.resume = args.flag("--resume");
  if (run.jobs < 1) throw InputError("--jobs: expected a positive integer");
  if (mpi && mpi->size() > 1 && !study.basins)
    throw InputError("mpirun -np " + std::to_string(mpi->size()) + ": " + study.path +
                     " has no [basins]: the ranks share a walk's runs, and a study without one "
                     "would be computed by each; expected a study with [basins], or no mpirun");
  if (run.writes()) std::filesystem::create_directories(out);

  // Every branch's case, set and start checked before anything is computed: a metronome case
  // file or an equation case file (compiled once, its values per branch).
  auto& systems = run.systems;
  auto& sources = run.sources;
  std::vector<std::optional<RecordedPeriod>> recorded;  // each branch's start_data, if any
  for (auto& b : study.branches) {
    auto c = std::make_unique<LoadedSystem>(study.case_path, study.params, b.sets, std::nullopt,
                                            "a branch", b.saved, study.escapement);
    c->require_orbits();
    if (c->saved_orbit())  // on the segments it was resolved on, as continue's --from-point
      b.request.continuation.orbit.shooting.segments = c->saved_orbit()->segments;
    if (!c->system().autonomous() && !b.transient_given) b.request.continuation.orbit.transient = 0;
    if (!b.request.switch_at.empty()) c->require_autonomous("switch_at (branch switching)");
    if (!b.request.parent_path.empty()) {
      // Saved equilibria for an HBn switch: read and checked now, before any work.
      const EquilibriumBranch saved = read_equilibria_json(b.request.parent_path, c->system());
      if (saved.parameter_name != study.parameter)
        throw InputError(study.path + ": branch '" + b.name + "': equilibria " +
                         b.request.parent_path + " are in " + saved.parameter_name +
                         "; expected them in " + study.parameter);
    }
    const auto names = c->system().parameter_names();
    if (std::find(names.begin(), names.end(), study.parameter) == names.end())
      throw InputError(study.path + ": parameter '" + study.parameter + "' is not one of " +
                       c->path() + "'s: " + join(names));
    recorded.push_back(b.start_data.empty() ? std::nullopt
                                            : std::optional<RecordedPeriod>(read_recorded_period(
                                                  b.start_data, c->system().state_names(),
                                                  c->path(), c->system().angle_states())));
    std::vector<std::pair<std::string, double>> ends{
        {study.path + ": branch '" + b.name + "': from", b.request.from},
        {study.path + ": branch '" + b.name + "': to", b.request.to}};
    if (b.request.at) ends.push_back({study.path + ": branch '" + b.name + "': at", *b.request.at});
    c->check_range(study.parameter, ends);
    for (const bool stop : {false, true})
      for (const Assignment& a : stop ? b.stops : b.user_values)
        b.request.continuation.user_values.push_back(
            user_value(a, stop, c->system(),
                       a.source + ": key 'branches." + b.name + "." +
                           (stop ? "stop_at" : "user_value") + "'"));
    // The family born at a Hopf point of an [[equilibria]] entry needs no start; a metronome
    // case's source still names one (unused), as continue --parent HOPF.json's.
    if (!b.equilibria_parent.empty() && b.request.start.empty() && !c->equations() &&
        !c->start_names().empty())
      b.request.start = c->start_names().front();
    if (!c->equations() && b.request.start.empty() && b.start_data.empty() && !b.saved)
      throw InputError(study.path + ": branch '" + b.name +
                       "': key 'start' is missing; expected the name of one of " + c->path() +
                       "'s starts: " + join(c->start_names()));
    sources.push_back(c->source(b.request.start, b.request.initial, recorded.back()));
    systems.push_back(std::move(c));
  }
  std::vector<std::pair<std::string, std::string>> equilibria_outputs;
  prepare_study_equilibria(run, equilibria_outputs);
  if (!run.writes())
    for (auto& r : run.equilibria_requests) r.csv_path.clear();
  const LoadedSystem& first = run.first();
  for (const auto& set : study.marks) {
    const auto values = first.set_values(set);  // throws naming the set if the case has none
    const auto it = std::find_if(values.begin(), values.end(),
                                 [&](const auto& v) { return v.first == study.parameter; });
    if (it == values.end())
      throw InputError(study.path + ": marks: parameter set '" + set + "' gives no value of " +
                       study.parameter);
    run.marks.emplace_back(set, it->second);
  }

  // Every output named before any work: one CSV per branch (two branches of one name would
  // write one file from two threads) and the JSON, none replacing an input or another.
  run.json_path = out + "/" + study.name + ".json";
  const std::string& json_path = run.json_path;
  std::vector<std::pair<std::string, std::string>> outputs{{"the study's JSON", json_path}};
  for (const auto& b : study.branches) {
    const std::string stem = out + "/" + study.name + "-" + b.name;
    outputs.emplace_back("branch '" + b.name + "''s CSV", stem + ".csv");
    outputs.emplace_back("branch '" + b.name + "''s events CSV", stem + "-events.csv");
  }
  outputs.insert(outputs.end(), equilibria_outputs.begin(), equilibria_outputs.end());
  prepare_study_basins(run, outputs);
  if (run.writes())
    for (const auto& [what, path] : outputs) check_writable(path, study.path + ": " + what);
  std::vector<std::pair<std::string, std::string>> inputs{{"study file", study.path},
                                                          {"case file", first.path()}};
  for (const auto& b : study.branches)
    if (!b.start_data.empty())
      inputs.emplace_back("branch '" + b.name + "''s start_data", b.start_data);
  for (const auto& e : study.equilibria)
    if (e.saved) inputs.emplace_back("equilibria '" + e.name + "''s parent", e.saved->path);
  check_distinct_outputs(outputs, inputs);
  if (run.resume && !run.basins_options)
    throw InputError("--resume: " + study.path +
                     " has no [basins] walk to resume; expected a study with [basins]");
  if (run.basins_options) {
    run.basins_record = study_record(args, inputs, {"--jobs", "--out", "--resume", "--quiet"});
    if (run.writes()) open_study_basins_journal(run);
  }

  auto& requests = run.requests;
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    const auto& b = study.branches[i];
    BranchRequest r = b.request;
    r.start_data = recorded[i];
    if (args.has("--accuracy")) apply_accuracy(accuracy(args), r.continuation);
    if (run.writes()) {
      r.csv_path = out + "/" + study.name + "-" + b.name + ".csv";
      r.events_path = out + "/" + study.name + "-" + b.name + "-events.csv";
    }
    r.progress = nullptr;
    requests.push_back(r);
  }
  run.results.resize(study.branches.size());
  run.errors.resize(study.branches.size());
  return run;
}

namespace {

// The jobs a study job starts from (job numbers as StudyRun's: branches, then equilibria
// entries): a branch switched at another's event, or at a Hopf point of an equilibria entry; an
// entry switched at another's BP.
std::vector<std::vector<std::size_t>> job_parents(const Study& study) {
  const std::size_t branches = study.branches.size();
  const auto branch = [&](const std::string& name) {
    std::size_t i = 0;
    while (study.branches[i].name != name) ++i;
    return i;
  };
  const auto equilibria = [&](const std::string& name) {
    std::size_t k = 0;
    while (study.equilibria[k].name != name) ++k;
    return branches + k;
  };
  std::vector<std::vector<std::size_t>> parents(branches + study.equilibria.size());
  for (std::size_t i = 0; i < branches; ++i) {
    const StudyBranch& b = study.branches[i];
    if (!b.parent.empty()) parents[i].push_back(branch(b.parent));
    if (!b.equilibria_parent.empty()) parents[i].push_back(equilibria(b.equilibria_parent));
  }
  for (std::size_t k = 0; k < study.equilibria.size(); ++k)
    if (!study.equilibria[k].parent.empty())
      parents[branches + k].push_back(equilibria(study.equilibria[k].parent));
  return parents;
}

}  // namespace

void run_study_branches(StudyRun& run, const std::atomic<bool>* stop,
                        const JobCallbacks& callbacks) {
  const Study& study = run.study;
  auto& results = run.results;
  auto& errors = run.errors;
  auto& requests = run.requests;
  const auto& sources = run.sources;
  const std::size_t branches = study.branches.size(), jobs = run.job_count();
  // The equilibria entries first (cheap, and what Hopf switches start from), then the branches,
  // each once every job it starts from is done.
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < study.equilibria.size(); ++k) order.push_back(branches + k);
  for (std::size_t i = 0; i < branches; ++i) order.push_back(i);
  const auto parents = job_parents(study);
  std::mutex queue;  // guards taken and done
  std::condition_variable finished;
  std::vector<bool> taken(jobs, false), done(jobs, false);
  // Where each running branch is (on the status line of a terminal).
  if (callbacks.job)
    for (std::size_t i = 0; i < requests.size(); ++i)
      requests[i].on_point = [&, i, own = requests[i].on_point](const ContinuationPoint& p) {
        if (own) own(p);
        callbacks.job(i, study.branches[i].name + " " + requests[i].parameter + " = " +
                             format_number(p.parameter));
      };
  const auto run_branch_job = [&](std::size_t i) {
    const StudyBranch& b = study.branches[i];
    if (!b.parent.empty()) {
      std::size_t p = 0;
      while (study.branches[p].name != b.parent) ++p;
      if (!errors[p].empty() || !results[p].started())
        throw std::runtime_error("its parent branch '" + b.parent + "' has no result");
      requests[i].parent_branch = &results[p];
    }
    if (!b.equilibria_parent.empty()) {
      std::size_t k = 0;
      while (study.equilibria[k].name != b.equilibria_parent) ++k;
      if (!run.equilibria_errors[k].empty() || !run.equilibria_results[k].started())
        throw std::runtime_error("its equilibria '" + b.equilibria_parent + "' have no result");
      requests[i].parent_equilibria = &run.equilibria_results[k];
    }
    results[i] = run_branch(sources[i], requests[i], stop);
  };
  auto worker = [&] {
    for (;;) {
      std::size_t i = jobs;
      {
        std::unique_lock<std::mutex> lock(queue);
        finished.wait(lock, [&] {
          if (std::all_of(taken.begin(), taken.end(), [](bool t) { return t; })) return true;
          for (const std::size_t j : order)
            if (!taken[j] && std::all_of(parents[j].begin(), parents[j].end(),
                                         [&](std::size_t p) { return bool(done[p]); })) {
              i = j;
              return true;
            }
          return false;
        });
        if (i == jobs) return;  // every job taken
        taken[i] = true;
      }
      try {
        if (i < branches) {
          run_branch_job(i);
        } else {
          run_study_equilibria(run, i - branches, stop, [&, i](const std::string& doing) {
            if (callbacks.job) callbacks.job(i, doing);
          });
        }
      } catch (const std::exception& e) {
        (i < branches ? errors[i] : run.equilibria_errors[i - branches]) = e.what();
      }
      if (callbacks.finished) callbacks.finished(i);
      {
        std::lock_guard<std::mutex> lock(queue);
        done[i] = true;
      }
      finished.notify_all();
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::min<int>(run.jobs, static_cast<int>(jobs)); ++t)
    threads.emplace_back(worker);
  for (auto& t : threads) t.join();
  // A line per job, in the study's order (the same on every run, whichever finished first;
  // on a terminal the status line showed them as they went).
  if (!callbacks.log) return;
  for (std::size_t i = 0; i < branches; ++i) {
    char line[160];
    std::snprintf(line, sizeof line, "  branch %-14s %zu points in %.1f s; ",
                  study.branches[i].name.c_str(), results[i].points.size(), results[i].seconds);
    callbacks.log(line + (!errors[i].empty() ? errors[i] : results[i].stop_reason) + "\n");
  }
  for (std::size_t k = 0; k < study.equilibria.size(); ++k) {
    const EquilibriumBranch& e = run.equilibria_results[k];
    char line[160];
    std::snprintf(line, sizeof line, "  equilibria %-10s %zu points in %.1f s; ",
                  study.equilibria[k].name.c_str(), e.points.size(), e.seconds);
    const std::string& error = run.equilibria_errors[k];
    callbacks.log(line + (!error.empty() ? error : e.stop_reason) + "\n");
  }
}

void write_study_json(const StudyRun& run, double seconds) {
  const Study& study = run.study;
  const LoadedSystem& first = run.first();
  nlohmann::json j;
  j["study"] = study.name;
  j["title"] = study.title;
  j["case"] = first.path();
  j["params_set"] = first.params();
  j["parameter"] = study.parameter;
  j["axis"] = study.axis;
  j["branches"] = nlohmann::json::array();
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    nlohmann::json b = branch_json(run.results[i], run.requests[i], run.systems[i]->describer());
    b["name"] = study.branches[i].name;
    b["csv"] = std::filesystem::path(run.requests[i].csv_path).filename().string();
    if (!run.errors[i].empty()) b["error"] = run.errors[i];
    j["branches"].push_back(b);
  }
  j["equilibria"] = nlohmann::json::array();
  for (std::size_t k = 0; k < study.equilibria.size(); ++k) {
    const EquilibriaRequest& r = run.equilibria_requests[k];
    nlohmann::json e = equilibria_json(r, run.equilibria_results[k], *run.equilibria_systems[k]);
    e["name"] = study.equilibria[k].name;
    e["csv"] = std::filesystem::path(r.csv_path).filename().string();
    if (!run.equilibria_errors[k].empty()) e["error"] = run.equilibria_errors[k];
    j["equilibria"].push_back(e);
  }
  if (!study.equilibria.empty()) j["equilibria_axis"] = run.equilibria_axis;
  j["marks"] = nlohmann::json::array();
  for (const auto& [set, value] : run.marks)
    j["marks"].push_back({{"name", set}, {"value", value}});
  if (run.basins) j["basins"] = study_basins_json(run);
  j["seconds"] = seconds;
  write_json(run.json_path, j);
}

}  // namespace sympathy::app
