#include "cases/app/study_run.hpp"

#include <algorithm>
#include <cmath>
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

StudyRun study_run(const Arguments& args) {
  StudyRun run;
  run.study = load_study(args.positional(0));
  Study& study = run.study;
  run.out = args.text("--out", "out/figures");
  const std::string& out = run.out;
  run.jobs = args.integer("--jobs", 2);
  if (run.jobs < 1) throw InputError("--jobs: expected a positive integer");
  std::filesystem::create_directories(out);

  // Every branch's case, set and start checked before anything is computed: a metronome case
  // file or an equation case file (compiled once, its values per branch).
  auto& systems = run.systems;
  auto& sources = run.sources;
  std::vector<std::optional<RecordedPeriod>> recorded;  // each branch's start_data, if any
  for (auto& b : study.branches) {
    auto c = std::make_unique<LoadedSystem>(study.case_path, study.params, b.sets, std::nullopt,
                                            "a branch", b.saved);
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
    if (!c->equations() && b.request.start.empty() && b.start_data.empty() && !b.saved)
      throw InputError(study.path + ": branch '" + b.name +
                       "': key 'start' is missing; expected the name of one of " + c->path() +
                       "'s starts: " + join(c->start_names()));
    sources.push_back(c->source(b.request.start, b.request.initial, recorded.back()));
    systems.push_back(std::move(c));
  }
  const LoadedSystem& first = *systems.front();
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
  for (const auto& [what, path] : outputs) check_writable(path, study.path + ": " + what);
  std::vector<std::pair<std::string, std::string>> inputs{{"study file", study.path},
                                                          {"case file", first.path()}};
  for (const auto& b : study.branches)
    if (!b.start_data.empty())
      inputs.emplace_back("branch '" + b.name + "''s start_data", b.start_data);
  check_distinct_outputs(outputs, inputs);

  auto& requests = run.requests;
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    const auto& b = study.branches[i];
    BranchRequest r = b.request;
    r.start_data = recorded[i];
    if (args.has("--accuracy")) apply_accuracy(accuracy(args), r.continuation);
    r.csv_path = out + "/" + study.name + "-" + b.name + ".csv";
    r.events_path = out + "/" + study.name + "-" + b.name + "-events.csv";
    r.progress = nullptr;
    requests.push_back(r);
  }
  run.results.resize(study.branches.size());
  run.errors.resize(study.branches.size());
  return run;
}

void run_study_branches(StudyRun& run, const std::atomic<bool>* stop,
                        const JobCallbacks& callbacks) {
  const Study& study = run.study;
  auto& results = run.results;
  auto& errors = run.errors;
  auto& requests = run.requests;
  const auto& sources = run.sources;
  const int jobs = run.jobs;
  // Branches switched at another's event run after the others, from that branch's result.
  std::vector<std::size_t> order;
  for (int chained = 0; chained < 2; ++chained)
    for (std::size_t i = 0; i < study.branches.size(); ++i)
      if (study.branches[i].parent.empty() == (chained == 0)) order.push_back(i);
  const std::size_t independent = static_cast<std::size_t>(
      std::count_if(study.branches.begin(), study.branches.end(),
                    [](const StudyBranch& b) { return b.parent.empty(); }));
  std::mutex queue;  // guards next
  std::size_t next = 0;
  // Where each running branch is (on the status line of a terminal).
  if (callbacks.job)
    for (std::size_t i = 0; i < requests.size(); ++i)
      requests[i].on_point = [&, i, own = requests[i].on_point](const ContinuationPoint& p) {
        if (own) own(p);
        callbacks.job(i, study.branches[i].name + " " + requests[i].parameter + " = " +
                             format_number(p.parameter));
      };
  auto worker = [&](std::size_t end) {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> lock(queue);
        if (next >= end) return;
        i = order[next++];
      }
      try {
        if (const auto& parent = study.branches[i].parent; !parent.empty()) {
          std::size_t p = 0;
          while (study.branches[p].name != parent) ++p;
          if (!errors[p].empty() || !results[p].started())
            throw std::runtime_error("its parent branch '" + parent + "' has no result");
          requests[i].parent_branch = &results[p];
        }
        results[i] = run_branch(sources[i], requests[i], stop);
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
      if (callbacks.finished) callbacks.finished(i);
    }
  };
  for (const std::size_t end : {independent, order.size()}) {
    std::vector<std::thread> threads;
    for (int t = 0; t < std::min<int>(jobs, static_cast<int>(study.branches.size())); ++t)
      threads.emplace_back(worker, end);
    for (auto& t : threads) t.join();
  }
  // A line per branch, in the study's order (the same on every run, whichever finished first;
  // on a terminal the status line showed them as they went).
  if (!callbacks.log) return;
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    char line[160];
    std::snprintf(line, sizeof line, "  branch %-14s %zu points in %.1f s; ",
                  study.branches[i].name.c_str(), results[i].points.size(), results[i].seconds);
    callbacks.log(line + (!errors[i].empty() ? errors[i] : results[i].stop_reason) + "\n");
  }
}

void write_study_json(const StudyRun& run, double seconds) {
  const Study& study = run.study;
  const LoadedSystem& first = *run.systems.front();
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
  j["marks"] = nlohmann::json::array();
  for (const auto& [set, value] : run.marks)
    j["marks"].push_back({{"name", set}, {"value", value}});
  j["seconds"] = seconds;
  write_json(run.json_path, j);
}

}  // namespace sympathy::app
