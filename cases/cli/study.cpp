// sympathy study: the branches that make one figure, described in a study file next to a case
// (cases/figures/*.toml), computed side by side; a CSV per branch and one JSON for the figure.
#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <mutex>
#include <thread>

#include "cases/cli/branch_run.hpp"
#include "cases/cli/commands.hpp"
#include "sympathy/continuation/branch_output.hpp"

namespace sympathy::cli {

namespace {

struct StudyBranch {
  std::string name;
  BranchRequest request;
  std::vector<Assignment> sets;  // on top of the study's parameter set
};

struct Study {
  std::string path, name, title, case_path, params, parameter, axis;
  std::vector<StudyBranch> branches;
};

Study load_study(const std::string& path) {
  const toml::table root = read_toml(path, "study file");
  const TomlReader in(path);
  in.only(root, "", {"title", "case", "params", "parameter", "axis", "branches"});
  Study s;
  s.path = path;
  s.name = std::filesystem::path(path).stem().string();
  auto required = [&](const char* key) -> const toml::node& {
    const toml::node* n = root.get(key);
    if (!n) throw InputError(path + ": key '" + key + "' is missing");
    return *n;
  };
  s.title = root.get("title") ? in.string(*root.get("title"), "title") : s.name;
  const std::string case_file = in.string(required("case"), "case");
  s.case_path = (std::filesystem::path(path).parent_path() / case_file).lexically_normal().string();
  if (root.get("params")) s.params = in.string(*root.get("params"), "params");
  s.parameter = in.string(required("parameter"), "parameter");
  s.axis = root.get("axis") ? in.string(*root.get("axis"), "axis") : "phase";
  if (s.axis != "phase" && s.axis != "frequency")
    in.fail(*root.get("axis"), "axis", "\"phase\" or \"frequency\"");
  const toml::node& list = required("branches");
  if (!list.is_array_of_tables() || list.as_array()->empty())
    in.fail(list, "branches", "one or more [[branches]] tables");
  int index = 0;
  for (const auto& entry : *list.as_array()) {
    ++index;
    const std::string prefix = "branches[" + std::to_string(index) + "].";
    const auto& t = *entry.as_table();
    in.only(t, prefix,
            {"name", "start", "from", "to", "at", "set", "initial", "max_points", "step",
             "max_step", "transient"});
    StudyBranch b;
    for (const char* key : {"name", "start", "from", "to"})
      if (!t.get(key))
        throw InputError(path + ":" + std::to_string(entry.source().begin.line) + ": key '" +
                         prefix + key + "' is missing");
    b.name = in.string(*t.get("name"), prefix + "name");
    b.request.start = in.string(*t.get("start"), prefix + "start");
    b.request.parameter = s.parameter;
    b.request.from = in.number(*t.get("from"), prefix + "from");
    b.request.to = in.number(*t.get("to"), prefix + "to");
    if (auto* n = t.get("at")) b.request.at = in.number(*n, prefix + "at");
    auto& o = b.request.continuation;
    if (auto* n = t.get("transient")) o.orbit.transient = in.number(*n, prefix + "transient");
    if (auto* n = t.get("max_points")) o.max_points = in.integer(*n, prefix + "max_points");
    if (auto* n = t.get("step")) o.initial_step = in.number(*n, prefix + "step");
    if (auto* n = t.get("max_step")) o.max_step = in.number(*n, prefix + "max_step");
    // The engine's own validation, as the command line's (the same domains, named by key).
    const std::string where =
        path + ":" + std::to_string(entry.source().begin.line) + ": " + prefix;
    check_options(o.validate(), where);
    if (b.request.from == b.request.to)
      throw InputError(where + "from, " + prefix + "to: expected different values");
    if (b.request.at && !(*b.request.at > std::min(b.request.from, b.request.to) &&
                          *b.request.at < std::max(b.request.from, b.request.to)))
      throw InputError(where + "at: expected a value between from and to");
    for (const char* group : {"set", "initial"}) {
      const toml::node* n = t.get(group);
      if (!n) continue;
      if (!n->is_table()) in.fail(*n, prefix + group, "a table of NAME = VALUE");
      for (auto&& [k, v] : *n->as_table()) {
        Assignment a{std::string(k.str()),
                     in.number(v, prefix + group + "." + std::string(k.str())), in.where(v)};
        (std::string(group) == "set" ? b.sets : b.request.initial).push_back(a);
      }
    }
    s.branches.push_back(std::move(b));
  }
  return s;
}

}  // namespace

int run_study(const std::vector<std::string>& argv) {
  Arguments args("study", argv,
                 {{"--out", "DIR", false, "where the CSV and JSON files go (default out/figures)"},
                  {"--jobs", "N", false, "branches computed side by side (default 2)"}},
                 {"STUDY"});
  Stopwatch clock;
  const Study study = load_study(args.positional(0));
  const std::string out = args.text("--out", "out/figures");
  const int jobs = args.integer("--jobs", 2);
  if (jobs < 1) throw InputError("--jobs: expected a positive integer");
  std::filesystem::create_directories(out);

  // Every branch's case, set and start checked before anything is computed.
  const CaseFile file = CaseFile::load(study.case_path);
  std::vector<LoadedCase> cases;
  for (const auto& b : study.branches) {
    LoadedCase c{file, study.params.empty() ? file.default_parameter_set() : study.params, {}};
    c.spec = file.spec(c.params, b.sets);
    if (!c.spec.has_parameter(study.parameter))
      throw InputError(study.path + ": parameter '" + study.parameter + "' is not one of " +
                       file.path() + "'s: " + join(c.spec.parameter_names()));
    file.start(b.request.start);
    std::vector<double> ends{b.request.from, b.request.to};
    if (b.request.at) ends.push_back(*b.request.at);
    check_parameter_range(c.spec, study.parameter, ends,
                          study.path + ": branch '" + b.name + "': ");
    cases.push_back(std::move(c));
  }

  // Every output named before any work: one CSV per branch (two branches of one name would
  // write one file from two threads) and the JSON, none replacing an input or another.
  const std::string json_path = out + "/" + study.name + ".json";
  std::vector<std::pair<std::string, std::string>> outputs{{"the study's JSON", json_path}};
  for (const auto& b : study.branches) {
    const std::string stem = out + "/" + study.name + "-" + b.name;
    outputs.emplace_back("branch '" + b.name + "''s CSV", stem + ".csv");
    outputs.emplace_back("branch '" + b.name + "''s events CSV", stem + "-events.csv");
  }
  for (const auto& [what, path] : outputs) check_writable(path, study.path + ": " + what);
  check_distinct_outputs(outputs, {{"study file", study.path}, {"case file", file.path()}});

  std::printf("sympathy study %s: %s\n  case %s  params %s  parameter %s\n", study.path.c_str(),
              study.title.c_str(), file.path().c_str(), cases.front().params.c_str(),
              study.parameter.c_str());
  std::fflush(stdout);
  const auto* stop = interrupt_flag();
  std::vector<Branch> results(study.branches.size());
  std::vector<std::unique_ptr<MetronomeModel>> models;
  for (const auto& c : cases) models.push_back(std::make_unique<MetronomeModel>(c.spec));
  std::vector<BranchRequest> requests;
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    const auto& b = study.branches[i];
    BranchRequest r = b.request;
    r.csv_path = out + "/" + study.name + "-" + b.name + ".csv";
    r.events_path = out + "/" + study.name + "-" + b.name + "-events.csv";
    r.progress = nullptr;
    requests.push_back(r);
  }
  std::mutex print;
  std::size_t next = 0;
  std::vector<std::string> errors(study.branches.size());
  auto worker = [&] {
    for (;;) {
      std::size_t i;
      {
        std::lock_guard<std::mutex> lock(print);
        if (next >= study.branches.size()) return;
        i = next++;
      }
      try {
        results[i] = run_branch(cases[i], *models[i], requests[i], stop);
      } catch (const std::exception& e) {
        errors[i] = e.what();
      }
      std::lock_guard<std::mutex> lock(print);
      std::printf("  branch %-14s %zu points in %.1f s; %s\n", study.branches[i].name.c_str(),
                  results[i].points.size(), results[i].seconds,
                  !errors[i].empty() ? errors[i].c_str() : results[i].stop_reason.c_str());
      std::fflush(stdout);
    }
  };
  std::vector<std::thread> threads;
  for (int t = 0; t < std::min<int>(jobs, static_cast<int>(study.branches.size())); ++t)
    threads.emplace_back(worker);
  for (auto& t : threads) t.join();

  nlohmann::json j;
  j["study"] = study.name;
  j["title"] = study.title;
  j["case"] = file.path();
  j["params_set"] = cases.front().params;
  j["parameter"] = study.parameter;
  j["axis"] = study.axis;
  j["branches"] = nlohmann::json::array();
  bool ok = true;
  for (std::size_t i = 0; i < study.branches.size(); ++i) {
    nlohmann::json b = branch_json(results[i], requests[i], *models[i]);
    b["name"] = study.branches[i].name;
    b["csv"] = std::filesystem::path(requests[i].csv_path).filename().string();
    if (!errors[i].empty()) b["error"] = errors[i];
    j["branches"].push_back(b);
    ok = ok && errors[i].empty() && results[i].started();
    std::printf("bifurcations on %s:\n", study.branches[i].name.c_str());
    print_events(stdout, results[i]);
  }
  j["seconds"] = clock.seconds();
  write_json(json_path, j);
  std::printf("  wrote %s, %zu CSV files of points and %zu of events; run time %.2f s\n",
              json_path.c_str(), study.branches.size(), study.branches.size(), clock.seconds());
  if (!ok) return 4;
  const bool interrupted = std::any_of(results.begin(), results.end(), [](const Branch& b) {
    return b.stop == StopReason::Interrupted;
  });
  return interrupted ? kInterrupted : 0;
}

}  // namespace sympathy::cli
