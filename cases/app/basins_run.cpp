#include "cases/app/basins_run.hpp"

#include "cases/app/basins_file.hpp"
#include "cases/app/case_arguments.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include <nlohmann/json.hpp>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"
#include "sympathy/core/quartiles.hpp"

namespace sympathy::app {

std::vector<std::string> journal_header(const BasinStudy& study) {
  std::vector<std::string> h{"point"};
  for (const auto& a : study.options().grid) h.push_back(a.parameter);
  h.push_back("start");
  for (int i = 1; i <= study.pendula(); ++i) h.push_back("th" + std::to_string(i) + "_0");
  h.insert(h.end(), {"class", "t_sync", "frequency"});
  for (int i = 2; i <= study.pendula(); ++i) h.push_back("phase_th" + std::to_string(i));
  for (int i = 1; i <= study.pendula(); ++i) h.push_back("amp_th" + std::to_string(i));
  if (study.options().confirm)
    h.insert(h.end(), {"orbit", "orbit_period", "orbit_stability", "orbit_max_multiplier"});
  if (study.options().early_stop) h.insert(h.end(), {"stopped_at", "certified_by"});
  return h;
}

std::vector<std::string> task_fields(const BasinTask& t) {
  std::vector<std::string> f{std::to_string(t.point)};
  for (double v : t.values) f.push_back(format_double(v));
  f.push_back(std::to_string(t.start));
  for (double a : t.angles) f.push_back(format_double(a));
  return f;
}

std::vector<std::string> row_of(const BasinTask& t, const BasinRun& run, const BasinOptions& o) {
  const bool confirm = o.confirm;
  const SyncResult& r = run.sync;
  auto f = task_fields(t);
  f.insert(f.end(), {r.name, format_double(r.time_to_sync), format_double(r.frequency)});
  for (double v : r.phase_differences) f.push_back(format_double(v));
  for (double v : r.amplitudes) f.push_back(format_double(v));
  if (confirm) {
    // The orbit Newton converged to from the run's end, or why not; "-" where nothing was locked.
    if (!run.orbit) {
      f.insert(f.end(), {"-", "nan", "-", "nan"});
    } else {
      const OrbitConfirmation& c = *run.orbit;
      f.insert(f.end(), {c.converged ? "converged" : to_string(c.outcome), format_double(c.period),
                         c.converged ? to_string(c.stability) : "-", format_double(c.max_modulus)});
    }
  }
  // Where the run stopped, and the candidate orbit (its start) that certified it ("-": none).
  if (o.early_stop)
    f.insert(f.end(),
             {format_double(run.stopped_at), run.certified_by.empty() ? "-" : run.certified_by});
  return f;
}

std::vector<std::vector<BasinShare>> write_basins(const Basins& b) {
  const BasinStudy& study = *b.study;
  const BasinOptions& o = b.o;
  const TaskJournal& journal = *b.journal;
  std::vector<std::pair<std::size_t, std::string>> outcomes;
  // Per point and state, the runs' times to synchronize (the column after the class).
  std::vector<std::map<std::string, std::vector<double>>> times(study.points());
  for (const auto& [index, row] : journal.rows()) {
    const std::size_t point = study.task(index).point;
    outcomes.emplace_back(point, row[b.identity_fields]);
    times[point][row[b.identity_fields]].push_back(
        std::strtod(row[b.identity_fields + 1].c_str(), nullptr));
  }
  const auto shares = basin_shares(study.points(), outcomes);
  write_file_atomically(b.runs_path, journal.table());

  std::vector<std::string> share_header{"point"};
  for (const auto& a : o.grid) share_header.push_back(a.parameter);
  share_header.insert(share_header.end(), {"class", "count", "runs", "share", "lower", "upper",
                                           "t_sync_q1", "t_sync_median", "t_sync_q3"});
  std::string share_table = join(share_header, ",") + "\n";
  nlohmann::ordered_json json;
  if (!b.study_path.empty()) {
    json["study"] = b.study_path;
    json["title"] = b.title;
  }
  json["case"] = b.c.file.path();
  json["params"] = b.c.params;
  json["escapement"] = to_string(b.c.spec.escapement);
  for (const auto& a : o.grid)
    json["grid"].push_back(
        {{"parameter", a.parameter}, {"from", a.from}, {"to", a.to}, {"count", a.count}});
  json["starts"] = o.starts;
  json["angles"] = {o.angle_min, o.angle_max};
  json["initial"] = nlohmann::ordered_json::object();
  for (const auto& a : b.initial) json["initial"][a.key] = a.value;
  json["seed"] = o.seed;
  json["t_end"] = o.t_end;
  json["dt"] = o.dt;
  json["classifier"] = {{"window", o.classifier.window},
                        {"phase_tolerance", o.classifier.phase_tolerance},
                        {"lock_tolerance", o.classifier.lock_tolerance},
                        {"stopped_amplitude", study.options().classifier.stopped_amplitude}};
  json["integrator"] = {
      {"method", to_string(o.flow.method)}, {"rtol", o.flow.rtol}, {"atol", o.flow.atol}};
  json["tasks"] = study.tasks();
  json["done"] = journal.rows().size();
  json["complete"] = journal.rows().size() == study.tasks();
  json["runs_csv"] = std::filesystem::path(b.runs_path).filename().string();
  json["points"] = nlohmann::ordered_json::array();
  for (std::size_t p = 0; p < study.points(); ++p) {
    const auto values = study.values(p);
    nlohmann::ordered_json point;
    point["point"] = p;
    for (std::size_t a = 0; a < values.size(); ++a)
      point["values"][o.grid[a].parameter] = values[a];
    point["runs"] = shares[p].empty() ? 0 : shares[p].front().proportion.trials;
    point["shares"] = nlohmann::ordered_json::object();
    for (const auto& s : shares[p]) {
      const auto& q = s.proportion;
      // The state's times to synchronize: their quartiles (NaN where it is not locked or no
      // run ended in it).
      const Quartiles t = quartiles(times[p][s.state]);
      point["shares"][s.state] = {{"count", q.count},
                                  {"share", q.share},
                                  {"lower", q.lower},
                                  {"upper", q.upper},
                                  {"t_sync", {{"q1", t.q1}, {"median", t.median}, {"q3", t.q3}}}};
      std::vector<std::string> fields{std::to_string(p)};
      for (double v : values) fields.push_back(format_double(v));
      fields.insert(fields.end(),
                    {s.state, std::to_string(q.count), std::to_string(q.trials),
                     format_double(q.share), format_double(q.lower), format_double(q.upper),
                     format_double(t.q1), format_double(t.median), format_double(t.q3)});
      share_table += join(fields, ",") + "\n";
    }
    json["points"].push_back(point);
  }
  write_file_atomically(b.shares_path, share_table);
  write_file_atomically(b.json_path, json.dump(2) + "\n");

  return shares;
}

namespace {

// The command line's option for a field of BasinOptions.
std::string option_of(const std::string& field) {
  if (field.rfind("grid", 0) == 0) return "--grid";
  if (field == "starts") return "--starts";
  if (field == "angle_min" || field == "angle_max") return "--angles";
  if (field == "t_end") return "--t-end";
  if (field == "dt") return "--dt";
  if (field == "classifier.window") return "--window";
  if (field == "classifier.phase_tolerance") return "--phase-tolerance";
  if (field == "classifier.lock_tolerance") return "--lock-tolerance";
  if (field.rfind("flow.", 0) == 0) return "--" + field.substr(5);
  if (field.rfind("orbit.", 0) == 0) return "--accuracy (" + field + ")";
  return field;
}

void parse_study_options(const Arguments& args, Basins& b);

}  // namespace

std::function<std::optional<TaskRow>(std::size_t)> basins_tasks(const BasinStudy& study,
                                                                const std::atomic<bool>* stop) {
  return [&study, stop](std::size_t index) -> std::optional<TaskRow> {
    const BasinTask task = study.task(index);
    const auto result = study.run(task, stop);
    if (!result) return std::nullopt;
    return row_of(task, *result, study.options());
  };
}

namespace {

// The case of a basins study file, with its parameter set and `set` values.
LoadedCase load_case_of(const BasinsFile& f) {
  LoadedCase c{CaseFile::load(f.case_path), "", {}};
  c.params = f.params.empty() ? c.file.default_parameter_set() : f.params;
  c.spec = c.file.spec(c.params, f.sets);
  return c;
}

}  // namespace

Basins prepare_basins(const Arguments& args, int ranks) {
  // A basins study file sets the study; the command line then only says where and how to run it.
  const std::string input = args.positional(0);
  std::optional<BasinsFile> study_file;
  if (is_basins_file(input)) {
    study_file = load_basins_file(input);
    for (const char* option :
         {"--params", "--set", "--grid", "--starts", "--angles", "--initial", "--seed", "--t-end",
          "--dt", "--window", "--phase-tolerance", "--lock-tolerance", "--confirm", "--early-stop"})
      if (args.has(option))
        throw InputError(std::string(option) + ": given with the basins study file " + input +
                         ", which sets the study; expected it in the file");
  }
  Basins b;
  b.c = study_file ? load_case_of(*study_file) : load_case(args);
  BasinOptions& o = b.o;
  if (study_file) {
    b.study_path = study_file->path;
    b.title = study_file->title;
    o = study_file->options;
    b.initial = study_file->initial;
  } else {
    parse_study_options(args, b);
  }
  // Runs that stop early integrate at the accuracy a classification needs (the options given
  // still override it).
  o.flow = flow_options(
      args, o.early_stop ? BasinOptions::classification_flow() : BasinOptions::default_flow());
  apply_accuracy(accuracy(args), o.orbit);
  if (o.early_stop)
    // The candidate orbits come from every start of the case (each in its invariant subspace).
    for (const auto& name : b.c.file.start_names()) {
      const StartSpec& start = b.c.file.start(name);
      o.candidate_starts.push_back({name, b.c.file.initial_state(&start),
                                    b.c.file.invariant_subspace(start, MetronomeModel(b.c.spec))});
    }
  if (o.early_stop && o.candidate_starts.empty())
    throw InputError(std::string(study_file ? "early_stop" : "--early-stop") + ": the case file " +
                     b.c.file.path() +
                     " has no starts; expected [starts] to reach the candidate "
                     "orbits from");
  if (const auto problem = o.validate())
    throw InputError(option_of(problem->field) + ": expected " + problem->expected);
  b.run.threads = args.integer("--threads", 0);
  if (args.has("--threads") && b.run.threads < 1)
    throw InputError("--threads: expected a positive number of threads");

  const MetronomeModel model(b.c.spec);
  const auto names = model.state_names();
  for (const auto& a : b.initial)
    for (int i = 0; i < model.metronome_count(); ++i)
      if (a.key == names[model.angle_index(i)])
        throw InputError(a.source + ": the pendula's start angles are drawn at random (" +
                         (study_file ? "angles" : "--angles") +
                         "); expected a platform state or a velocity");
  const Eigen::VectorXd z0 = b.c.file.initial_state(nullptr, b.initial);
  b.study = std::make_unique<BasinStudy>(b.c.spec, z0, o);
  b.identity_fields = task_fields(b.study->task(0)).size();
  if (ranks > 1 && static_cast<std::size_t>(ranks - 1) > b.study->tasks())
    throw InputError("mpirun -np " + std::to_string(ranks) + ": " + std::to_string(ranks - 1) +
                     " workers for " + std::to_string(b.study->tasks()) + " runs; expected at " +
                     "most " + std::to_string(b.study->tasks() + 1) + " ranks (one manager)");

  b.out = args.text("--out", "out/basins");
  b.journal_path = b.out + "/basins_journal.csv";
  b.runs_path = b.out + "/basins_runs.csv";
  b.shares_path = b.out + "/basins_shares.csv";
  b.json_path = b.out + "/basins.json";
  check_distinct_outputs({{"journal", b.journal_path},
                          {"runs", b.runs_path},
                          {"shares", b.shares_path},
                          {"json", b.json_path}},
                         {{"case file", b.c.file.path()}, {"basins study file", b.study_path}});
  b.record =
      study_record(args, {{"case file", b.c.file.path()}, {"basins study file", b.study_path}},
                   {"--threads", "--out", "--resume"});
  return b;
}

namespace {

// The study as the command line gives it (no study file).
void parse_study_options(const Arguments& args, Basins& b) {
  BasinOptions& o = b.o;
  const auto grids = args.values("--grid");
  if (grids.empty())
    throw InputError("--grid: expected one or two parameter grids, e.g. k=40:90:6");
  for (const auto& g : grids) o.grid.push_back(parse_grid(g, "--grid"));
  o.starts = args.integer("--starts", o.starts);
  if (const auto angles = args.value("--angles")) {
    const auto colon = angles->find(':');
    const auto fail =
        InputError("--angles " + *angles + ": expected MIN:MAX in rad, e.g. -0.6:0.6");
    if (colon == std::string::npos) throw fail;
    try {
      std::size_t u1 = 0, u2 = 0;
      const std::string lo = angles->substr(0, colon), hi = angles->substr(colon + 1);
      o.angle_min = std::stod(lo, &u1);
      o.angle_max = std::stod(hi, &u2);
      if (u1 != lo.size() || u2 != hi.size()) throw fail;
    } catch (const std::logic_error&) {
      throw fail;
    }
    if (!(o.angle_max > o.angle_min))
      throw InputError("--angles " + *angles + ": the bounds are reversed or equal; expected " +
                       "MIN below MAX");
  }
  const int seed = args.integer("--seed", 1);
  if (seed < 0) throw InputError("--seed: expected a non-negative integer");
  o.seed = static_cast<std::uint64_t>(seed);
  o.t_end = args.number("--t-end", o.t_end);
  o.dt = args.number("--dt", o.dt);
  o.classifier.window = args.number("--window", o.classifier.window);
  o.classifier.phase_tolerance = args.number("--phase-tolerance", o.classifier.phase_tolerance);
  o.classifier.lock_tolerance = args.number("--lock-tolerance", o.classifier.lock_tolerance);
  o.confirm = args.flag("--confirm");
  o.early_stop = args.flag("--early-stop");
  b.initial = args.assignments("--initial");
}

}  // namespace

void open_basins_outputs(Basins& b, bool resume) {
  if (!resume && std::filesystem::exists(b.journal_path))
    throw InputError(
        "--out " + b.out + ": " + b.journal_path + " is the journal of an earlier " +
        "run; expected --resume to continue it, or another --out (or remove the file)");
  std::filesystem::create_directories(b.out);
  for (const auto& p : {b.journal_path, b.runs_path, b.shares_path, b.json_path})
    check_writable(p, "--out");
  check_or_write_study_record(b.journal_path, b.record,
                              resume && std::filesystem::exists(b.journal_path));
  const BasinStudy& study = *b.study;
  b.journal =
      std::make_unique<TaskJournal>(b.journal_path, journal_header(study), study.tasks(), resume);
  // A resumed journal must be of this study: each row's run (point, values, start, angles) the
  // one its task index gives now.
  for (const auto& [index, row] : b.journal->rows()) {
    const auto expected = task_fields(study.task(index));
    if (!std::equal(expected.begin(), expected.end(), row.begin()))
      throw InputError(b.journal_path + ": task " + std::to_string(index) + " is the run " +
                       join({row.begin(), row.begin() + b.identity_fields}, ",") +
                       "; this study's is " + join(expected, ",") +
                       " (expected a journal of the same case, grid, starts, angles and seed)");
  }
}

JournaledOutcome run_basins_here(const Arguments& args, const std::atomic<bool>* stop,
                                 const std::function<void(std::size_t, std::size_t)>& on_recorded) {
  Basins b = prepare_basins(args, 1);
  open_basins_outputs(b, args.flag("--resume"));
  const BasinStudy& study = *b.study;
  const MpiSession local;  // not under mpirun: one rank, the runs on threads
  const auto summary = run_journaled(local, study.tasks(), b.journal.get(),
                                     basins_tasks(study, stop), b.run, stop, [&](std::size_t done) {
                                       if (on_recorded) on_recorded(done, study.tasks());
                                     });
  b.journal->close();
  write_basins(b);
  return {b.json_path, summary.interrupted};
}

}  // namespace sympathy::app
