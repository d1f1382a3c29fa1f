// A study's [basins]: basin shares walked along the study's parameter (continuation/basin_walk.hpp)
// on the first branch's case at its values, the attractors named by the study's branches: a run
// that ends on an orbit of branch NAME counts under NAME, one on a stable orbit no branch holds
// under "new k", found by the runs and continued from value to value like the others.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include "cases/app/study_run.hpp"
#include "sympathy/continuation/basin_walk_journal.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy::app {

void prepare_study_basins(StudyRun& run,
                          std::vector<std::pair<std::string, std::string>>& outputs) {
  const Study& study = run.study;
  if (!study.basins) return;
  const StudyBasins& b = *study.basins;
  const LoadedSystem& c = *run.systems.front();
  const OdeSystem& system = c.system();
  c.check_range(study.parameter,
                {{b.where + ": basins.from", b.from}, {b.where + ": basins.to", b.to}});
  if (!c.equations() && b.start.empty())
    throw InputError(
        b.where + ": key 'basins.start' is missing; expected the name of one of " + c.path() +
        "'s starts (the states outside box keep its values): " + join(c.start_names()));
  const BranchSource start = c.source(b.start, {});
  BasinWalkOptions o;
  const auto parameters = system.parameter_names();
  o.parameter = static_cast<int>(std::find(parameters.begin(), parameters.end(), study.parameter) -
                                 parameters.begin());
  o.values = b.values();
  o.starts = b.starts;
  o.seed = b.seed;
  o.tasks.threads = b.threads;
  o.run = b.run;
  for (const auto& name : c.start_names()) o.symmetries.push_back(c.subspace(name));
  o.lower = o.upper = start.start_state;
  const auto states = system.state_names();
  for (const auto& r : b.box) {
    const auto it = std::find(states.begin(), states.end(), r.state);
    if (it == states.end())
      throw InputError(r.where + ": key 'basins.box." + r.state + "': not a state of " + c.path() +
                       "; expected one of: " + join(states));
    o.lower[it - states.begin()] = r.lower;
    o.upper[it - states.begin()] = r.upper;
  }
  if (auto wrong = o.validate(system.dimension(), system.parameter_count()))
    throw InputError(b.where + ": basins: " + wrong->message());
  run.basins_values = start.values;
  run.basins_options = std::move(o);
  run.basins_csv = run.out + "/" + study.name + "-basins.csv";
  outputs.emplace_back("the basins' CSV", run.basins_csv);
  run.basins_journal_path = run.out + "/" + study.name + "-basins-journal.csv";
  outputs.emplace_back("the basins' journal", run.basins_journal_path);
}

void open_study_basins_journal(StudyRun& run) {
  const std::string& path = run.basins_journal_path;
  const bool exists = std::filesystem::exists(path);
  if (!run.resume && exists)
    throw InputError("--out " + run.out + ": " + path +
                     " is the journal of an earlier walk; expected --resume to continue it, or "
                     "another --out (or remove the file)");
  check_or_write_study_record(path, run.basins_record, run.resume && exists);
  const BasinWalkOptions& o = *run.basins_options;
  run.basins_journal = std::make_unique<TaskJournal>(
      path, walk_journal_header(), o.values.size() * static_cast<std::size_t>(o.starts),
      run.resume);
}

std::vector<NamedBranch> study_basins_branches(const StudyRun& run) {
  std::vector<NamedBranch> branches;
  for (std::size_t i = 0; i < run.study.branches.size(); ++i)
    if (run.errors[i].empty() && run.results[i].started() &&
        run.results[i].parameter == run.basins_options->parameter)
      branches.push_back({run.study.branches[i].name, &run.results[i]});
  return branches;
}

std::vector<NamedEquilibria> study_basins_equilibria(const StudyRun& run) {
  std::vector<NamedEquilibria> equilibria;
  for (std::size_t k = 0; k < run.study.equilibria.size(); ++k)
    if (run.equilibria_errors[k].empty() && run.equilibria_results[k].started() &&
        run.equilibria_results[k].parameter == run.basins_options->parameter)
      equilibria.push_back({run.study.equilibria[k].name, &run.equilibria_results[k]});
  return equilibria;
}

namespace {

// A value's runs spread over the ranks of an MPI job (task_runner_mpi.hpp): rank 0 hands them out
// and records each fate as the worker that ran it sends it back (its journal row); then it sends
// the value's every row (the journal's for the runs read back from it) and whether the value was
// interrupted to the workers, which record the same fates and walk on, or stop, with it. Rows
// carry every bit of a fate that the walk reads (basin_walk_journal.hpp), so the ranks walk
// alike and the files equal a run's on threads.
BasinWalkOptions::ValueRunner mpi_runner(const MpiSession& mpi, const TaskJournal* journal,
                                         const std::size_t& value, const std::atomic<bool>* stop) {
  constexpr char kRowEnd = '\x1e', kField = '\x1f';
  return [&mpi, journal, &value, stop](
             std::size_t count, const std::vector<bool>& done,
             const std::function<std::optional<AttractorFate>(std::size_t)>& work,
             const std::function<void(std::size_t, AttractorFate &&)>& record) {
    const auto where = [&](std::size_t s) {
      return "rank 0: run " + std::to_string(s) + " of value " + std::to_string(value + 1);
    };
    std::vector<std::optional<TaskRow>> rows(count);
    TaskRunSummary summary;
    std::string text;
    if (mpi.rank() == 0) {
      summary = run_tasks_mpi(
          mpi, count, done, {},
          [&](std::size_t s, TaskRow&& row) {
            record(s, walk_journal_fate(row, where(s)));
            rows[s] = std::move(row);
          },
          stop);
      for (std::size_t s = 0; s < count; ++s)
        if (!done.empty() && done[s]) rows[s] = journal->rows().at(value * count + s);
      text = summary.interrupted ? "1" : "0";
      for (const auto& row : rows) {
        text += kRowEnd;
        if (!row) continue;
        text += '+';
        for (std::size_t f = 0; f < row->size(); ++f) {
          if (f > 0) text += kField;
          text += (*row)[f];
        }
      }
    } else {
      summary = run_tasks_mpi(
          mpi, count, {},
          [&](std::size_t s) -> std::optional<TaskRow> {
            auto fate = work(s);
            if (!fate) return std::nullopt;
            return walk_journal_row(0.0, s, *fate);
          },
          {}, stop);
    }
    mpi.broadcast(text);
    if (mpi.rank() > 0) {
      summary.tasks = count;
      summary.interrupted = text.front() == '1';
      std::size_t s = 0, from = 2;
      for (; s < count; ++s) {
        const std::size_t end = std::min(text.find(kRowEnd, from), text.size());
        if (end > from && text[from] == '+') {
          TaskRow row;
          std::size_t a = from + 1;
          for (std::size_t b; (b = text.find(kField, a)) < end; a = b + 1)
            row.push_back(text.substr(a, b - a));
          row.push_back(text.substr(a, end - a));
          record(s, walk_journal_fate(row, where(s)));
        }
        from = end + 1;
      }
    }
    return summary;
  };
}

}  // namespace

void run_study_basins(StudyRun& run, const std::atomic<bool>* stop,
                      const std::function<void(const std::string&)>& doing) {
  if (!run.basins_options) return;
  BasinWalkOptions o = *run.basins_options;
  const std::vector<NamedBranch> branches = study_basins_branches(run);
  std::size_t value = 0;  // the index of the value being walked
  o.on_value = [&](std::size_t j) {
    value = j;
    if (doing)
      doing("basins: " + run.study.parameter + " = " + format_number(o.values[j]) + " (" +
            std::to_string(j + 1) + " of " + std::to_string(o.values.size()) + ")");
  };
  TaskJournal* journal = run.basins_journal.get();  // rank 0's, or this machine's
  const auto starts = static_cast<std::size_t>(o.starts);
  if (journal) {
    o.on_run = [&](std::size_t task, const AttractorFate& fate) {
      journal->append(task, walk_journal_row(o.values[task / starts], task % starts, fate));
    };
    o.journaled = [&](std::size_t task) -> std::optional<AttractorFate> {
      const auto it = journal->rows().find(task);
      if (it == journal->rows().end()) return std::nullopt;
      return walk_journal_fate(it->second, journal->path() + ": task " + std::to_string(task));
    };
  }
  if (run.mpi && run.mpi->size() > 1) o.runner = mpi_runner(*run.mpi, journal, value, stop);
  run.basins = walk_basins(run.first().system(), run.basins_values, branches, o, stop,
                           study_basins_equilibria(run));
  if (!run.writes()) return;
  journal->close();
  CsvWriter csv(run.basins_csv,
                {"value", "attractor", "branch", "count", "trials", "share", "lower", "upper",
                 "certified_q1", "certified_median", "certified_q3"});
  for (const auto& v : run.basins->values)
    for (const auto& s : v.shares)
      csv.row({format_number(v.value), s.name, s.branch, std::to_string(s.proportion.count),
               std::to_string(s.proportion.trials), format_number(s.proportion.share),
               format_number(s.proportion.lower), format_number(s.proportion.upper),
               format_number(s.certified_at.q1), format_number(s.certified_at.median),
               format_number(s.certified_at.q3)});
  csv.close();
}

nlohmann::json study_basins_json(const StudyRun& run) {
  const BasinWalk& walk = *run.basins;
  const BasinWalkOptions& o = *run.basins_options;
  nlohmann::json j;
  j["csv"] = std::filesystem::path(run.basins_csv).filename().string();
  j["starts"] = o.starts;
  j["seed"] = o.seed;
  j["t_end"] = o.run.t_end;
  j["interrupted"] = walk.interrupted;
  j["values"] = nlohmann::json::array();
  j["shares"] = nlohmann::json::array();
  j["attractors"] = nlohmann::json::array();
  j["fates"] = nlohmann::json::array();
  j["runs"] = nlohmann::json::array();
  for (const auto& v : walk.values) j["values"].push_back(v.value);
  if (!walk.values.empty())
    for (std::size_t k = 0; k < walk.values.front().shares.size(); ++k) {
      nlohmann::json s;
      s["name"] = walk.values.front().shares[k].name;
      s["branch"] = walk.values.front().shares[k].branch;
      for (const char* key :
           {"count", "share", "lower", "upper", "certified_q1", "certified_median", "certified_q3"})
        s[key] = nlohmann::json::array();
      for (const auto& v : walk.values) {
        const Proportion& p = v.shares[k].proportion;
        s["count"].push_back(p.count);
        s["share"].push_back(p.share);
        s["lower"].push_back(p.lower);
        s["upper"].push_back(p.upper);
        // The certified runs' stop times' quartiles (null where none was certified).
        const Quartiles& q = v.shares[k].certified_at;
        for (const auto& [key, x] :
             {std::pair{"certified_q1", q.q1}, std::pair{"certified_median", q.median},
              std::pair{"certified_q3", q.q3}})
          s[key].push_back(std::isnan(x) ? nlohmann::json(nullptr) : nlohmann::json(x));
      }
      j["shares"].push_back(s);
    }
  for (const auto& v : walk.values) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& a : v.attractors) {
      const Eigen::VectorXd& z = a.at_rest() ? a.rest : a.orbit.state0;
      list.push_back({{"name", a.name},
                      {"branch", a.branch},
                      {"point", a.point},
                      {"at_rest", a.at_rest()},
                      {"period", a.at_rest() ? 0.0 : a.orbit.period},
                      {"max_multiplier", a.at_rest() ? 0.0 : a.orbit.floquet.max_modulus},
                      {"state", std::vector<double>(z.data(), z.data() + z.size())}});
    }
    j["attractors"].push_back(list);
    nlohmann::json fates = nlohmann::json::object();
    for (const Fate f : {Fate::Certified, Fate::Reached, Fate::NewOrbit, Fate::Equilibrium,
                         Fate::Torus, Fate::Unresolved, Fate::Failed})
      fates[to_string(f)] = std::count_if(v.runs.begin(), v.runs.end(),
                                          [&](const AttractorFate& r) { return r.fate == f; });
    j["fates"].push_back(fates);
    // Each run: how it ended, on which attractor, when it stopped, a torus' rotation number.
    nlohmann::json runs = nlohmann::json::array();
    for (const auto& r : v.runs) {
      nlohmann::json x = {{"fate", to_string(r.fate)},
                          {"attractor", r.attractor >= 0 ? v.attractors[r.attractor].name : ""},
                          {"stopped_at", r.stopped_at}};
      if (r.fate == Fate::Torus) x["rotation_number"] = r.rotation_number;
      if (!r.note.empty()) x["note"] = r.note;
      runs.push_back(x);
    }
    j["runs"].push_back(runs);
  }
  j["changes"] = nlohmann::json::array();
  for (const auto& c :
       share_changes(walk, study_basins_branches(run), study_basins_equilibria(run))) {
    nlohmann::json events = nlohmann::json::array();
    for (const auto& e : c.events)
      events.push_back({{"branch", e.branch},
                        {"type", e.type},
                        {"parameter", e.parameter},
                        {"uncertainty", e.uncertainty},
                        {"trusted", e.trusted}});
    j["changes"].push_back({{"name", c.name},
                            {"appears", c.appears},
                            {"before", c.before},
                            {"after", c.after},
                            {"present_before", c.present_before},
                            {"present_after", c.present_after},
                            {"events", events}});
  }
  return j;
}

}  // namespace sympathy::app
