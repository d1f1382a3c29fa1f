// sympathy basins: how often each synchronized state wins from random starts, over a grid of one
// or two parameters (cases/basin_study.hpp), run on every core (continuation/task_runner.hpp),
// every finished run streamed to a journal that a resumed run does not compute again
// (continuation/task_journal.hpp). Files, in --out DIR: basins_journal.csv (the runs as they
// finish), and at the end, in task order whatever the threads, basins_runs.csv, basins_shares.csv
// and basins.json (per grid point, each state's share with its 95% Wilson interval; written by
// basins_output). Under mpirun the same across the ranks of an MPI job
// (continuation/task_runner_mpi.hpp), with the same files.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "cases/app/basins_file.hpp"
#include "cases/app/task_run.hpp"
#include "cases/cli/basins_output.hpp"
#include "cases/cli/commands.hpp"
#include "cases/cli/common.hpp"
#include "cases/cli/progress.hpp"
#include "sympathy/cases/basin_study.hpp"
#include "sympathy/continuation/task_journal.hpp"
#include "sympathy/continuation/task_runner.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/output_file.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy::cli {

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

// Task index -> its run's journal row (nullopt where `stop` interrupted it).
std::function<std::optional<TaskRow>(std::size_t)> runs_of(const BasinStudy& study,
                                                           const std::atomic<bool>* stop) {
  return [&study, stop](std::size_t index) -> std::optional<TaskRow> {
    const BasinTask task = study.task(index);
    const auto result = study.run(task, stop);
    if (!result) return std::nullopt;
    return row_of(task, *result, study.options().confirm);
  };
}

// The case of a basins study file, with its parameter set and `set` values.
LoadedCase load_case_of(const BasinsFile& f) {
  LoadedCase c{CaseFile::load(f.case_path), "", {}};
  c.params = f.params.empty() ? c.file.default_parameter_set() : f.params;
  c.spec = c.file.spec(c.params, f.sets);
  return c;
}

// The options and the study, checked; no file touched. `ranks`: the MPI job's size (1 without).
Basins prepare_basins(const Arguments& args, int ranks) {
  // A basins study file sets the study; the command line then only says where and how to run it.
  const std::string input = args.positional(0);
  std::optional<BasinsFile> study_file;
  if (is_basins_file(input)) {
    study_file = load_basins_file(input);
    for (const char* option :
         {"--params", "--set", "--grid", "--starts", "--angles", "--initial", "--seed", "--t-end",
          "--dt", "--window", "--phase-tolerance", "--lock-tolerance", "--confirm"})
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
  o.flow = flow_options(args, BasinOptions::default_flow());
  apply_accuracy(accuracy(args), o.orbit);
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
  b.initial = args.assignments("--initial");
}

// The output directory and the journal (new, or resumed and checked to be of this study).
// Rank 0's alone: the other ranks of an MPI job write nothing.
void open_outputs(Basins& b, bool resume) {
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

}  // namespace

JournaledOutcome run_basins_here(const Arguments& args, const std::atomic<bool>* stop) {
  Stopwatch clock;
  Basins b = prepare_basins(args, 1);
  open_outputs(b, args.flag("--resume"));
  const BasinStudy& study = *b.study;
  const MpiSession local;  // not under mpirun: one rank, the runs on threads
  const auto summary =
      run_journaled(local, study.tasks(), b.journal.get(), runs_of(study, stop), b.run, stop);
  b.journal->close();
  write_results(b, summary, clock, nullptr);
  return {b.json_path, summary.interrupted};
}

int run_basins(const std::vector<std::string>& argv) {
  Arguments args("basins", argv, basins_options(), {"CASE|STUDY.toml"});
  Stopwatch clock;
  // Under mpirun: rank 0 manages (journal, files, messages), the others simulate. Every rank
  // checks the input; a failure on any rank ends every rank before any work, reported once.
  const MpiSession mpi;
  const bool distributed = mpi.size() > 1;
  std::optional<Basins> b;
  if (const auto exit = prepare_every_rank(mpi, [&] {
        b.emplace(prepare_basins(args, mpi.size()));
        if (mpi.rank() == 0) open_outputs(*b, args.flag("--resume"));
      }))
    return *exit;
  const BasinStudy& study = *b->study;
  const auto* stop = interrupt_flag();
  const auto work = runs_of(study, stop);
  if (distributed && mpi.rank() > 0) {
    run_journaled(mpi, study.tasks(), nullptr, work, b->run, stop);
    return 0;
  }

  TaskJournal& journal = *b->journal;
  const std::size_t to_compute = study.tasks() - journal.resumed();
  const int workers = distributed ? mpi.size() - 1 : b->run.resolved_threads(to_compute);
  if (!b->study_path.empty())
    std::fprintf(stderr, "sympathy basins %s: %s\n", b->study_path.c_str(), b->title.c_str());
  std::fprintf(stderr, "%s%s  params %s  escapement %s\n",
               b->study_path.empty() ? "sympathy basins " : "  case ", b->c.file.path().c_str(),
               b->c.params.empty() ? "(none)" : b->c.params.c_str(),
               to_string(b->c.spec.escapement).c_str());
  std::string grid_text;
  for (const auto& a : b->o.grid)
    grid_text += "  " + a.parameter + " " + format_number(a.from) + " .. " + format_number(a.to) +
                 " (" + std::to_string(a.count) + (a.count == 1 ? " value)" : " values)");
  std::fprintf(stderr,
               "  grid%s; %d starts a point, angles in [%g, %g] rad, seed %llu; %g s each\n",
               grid_text.c_str(), b->o.starts, b->o.angle_min, b->o.angle_max,
               static_cast<unsigned long long>(b->o.seed), b->o.t_end);
  std::fprintf(stderr, "  %zu runs: %zu in the journal, %zu to compute on %d %s%s\n", study.tasks(),
               journal.resumed(), to_compute, workers, distributed ? "MPI worker" : "thread",
               workers == 1 ? "" : "s");

  ProgressLine line(args.flag("--quiet"));
  const auto summary =
      run_journaled(mpi, study.tasks(), &journal, work, b->run, stop, [&](std::size_t done) {
        line.count("basins", done, study.tasks(), "runs", journal.resumed());
      });
  line.clear();
  journal.close();
  write_results(*b, summary, clock);
  return summary.interrupted ? kInterrupted : 0;
}

}  // namespace sympathy::cli
