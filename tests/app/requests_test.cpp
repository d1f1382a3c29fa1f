// Every command's request built from C++ without the command line, from typed values as a library
// user or the Python module gives them (no argv text), gives the program's numbers to the last
// digit: the same JSON (or CSV) as `sympathy COMMAND ... --json`, run times aside. The accuracy
// presets are the application layer's, so the default and fast presets are both compared.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cases/app/basins_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/fit_run.hpp"
#include "cases/app/map_run.hpp"
#include "cases/app/option_table.hpp"
#include "cases/app/orbit_run.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/simulation_run.hpp"
#include "cases/app/study_run.hpp"
#include "cases/app/sweep_run.hpp"

namespace sympathy {
namespace {

namespace fs = std::filesystem;

const std::string kSource = SYMPATHY_SOURCE_DIR;
const std::string kRow2 = kSource + "/cases/row2.toml";
const std::string kSingle = kSource + "/cases/single.toml";

app::GivenOption text(const std::string& name, const std::string& value = "") {
  app::GivenOption g;
  g.name = name;
  g.text = value;
  return g;
}
app::GivenOption number(const std::string& name, double value) {
  app::GivenOption g = text(name, std::to_string(value));
  g.number = value;
  return g;
}
app::GivenOption integer(const std::string& name, int value) {
  app::GivenOption g = text(name, std::to_string(value));
  g.integer = value;
  return g;
}
app::GivenOption assignment(const std::string& name, const std::string& key, double value) {
  app::GivenOption g = text(name, key + "=" + std::to_string(value));
  g.assignment = Assignment{key, value, name};
  return g;
}

app::Arguments typed(const std::string& command, const std::string& first,
                     std::vector<app::GivenOption> given) {
  const auto table = app::command_options(command);
  return app::Arguments(command, {first}, std::move(given), table.options, table.positional);
}

// A scratch directory per test, removed at its end.
class Requests : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("sympathy_requests_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // The program run with `args` (quoted for the shell, its output to a log); its exit code.
  int program(const std::vector<std::string>& args) const {
    std::string command = "'" + std::string(SYMPATHY_PROGRAM) + "'";
    for (const auto& a : args) command += " '" + a + "'";
    return std::system((command + " > '" + path("program.log") + "' 2>&1").c_str());
  }

  fs::path dir_;
};

// A JSON file without its run times (every key "seconds", at any depth).
nlohmann::json without_times(const std::string& path) {
  std::ifstream in(path);
  nlohmann::json j = nlohmann::json::parse(in);
  std::vector<nlohmann::json*> todo{&j};
  while (!todo.empty()) {
    nlohmann::json* node = todo.back();
    todo.pop_back();
    if (node->is_object()) {
      node->erase("seconds");
      for (auto& [key, value] : node->items()) todo.push_back(&value);
    } else if (node->is_array()) {
      for (auto& value : *node) todo.push_back(&value);
    }
  }
  return j;
}

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_F(Requests, OrbitAtTheDefaultAndTheFastPresetIsTheProgramsToTheLastDigit) {
  for (const std::string accuracy : {"default", "fast"}) {
    const app::OrbitRun run =
        app::run_orbit(typed("orbit", kRow2,
                             {text("--start", "anti-phase"), text("--accuracy", accuracy),
                              text("--json", path("library.json"))}));
    ASSERT_TRUE(run.orbit.converged());
    ASSERT_EQ(program({"orbit", kRow2, "--start", "anti-phase", "--accuracy", accuracy, "--json",
                       path("program.json")}),
              0)
        << file_text(path("program.log"));
    EXPECT_EQ(without_times(path("library.json")), without_times(path("program.json"))) << accuracy;
  }
}

TEST_F(Requests, BranchIsTheProgramsToTheLastDigit) {
  const app::Arguments args =
      typed("continue", kRow2,
            {text("--start", "anti-phase"), text("--param", "k"), number("--from", 44),
             number("--to", 50), text("--accuracy", "fast")});
  const app::LoadedSystem c = app::load_system(args);
  app::BranchRequest request = app::continue_request(args, c);
  request.progress = nullptr;
  const Branch branch = app::run_branch(c.source(request.start, request.initial), request, nullptr);
  ASSERT_FALSE(branch.events.empty());  // the BP near k = 47
  app::write_branch_json(path("library.json"), branch, request, c, 0.0);
  ASSERT_EQ(program({"continue", kRow2, "--start", "anti-phase", "--param", "k", "--from", "44",
                     "--to", "50", "--accuracy", "fast", "--json", path("program.json")}),
            0);
  EXPECT_EQ(without_times(path("library.json")), without_times(path("program.json")));
}

TEST_F(Requests, CurveIsTheProgramsToTheLastDigit) {
  const std::vector<std::string> words = {
      "--start",       "anti-phase", "--param",     "k",    "--from",     "44",
      "--to",          "50",         "--event",     "BP1",  "--second",   "c",
      "--second-from", "0.0185",     "--second-to", "0.02", "--accuracy", "fast"};
  const app::Arguments args =
      typed("curve", kRow2,
            {text("--start", "anti-phase"), text("--param", "k"), number("--from", 44),
             number("--to", 50), text("--event", "BP1"), text("--second", "c"),
             number("--second-from", 0.0185), number("--second-to", 0.02),
             text("--accuracy", "fast"), text("--json", path("library.json"))});
  const app::LoadedSystem c = app::load_system(args);
  const app::CurveRequest r = app::curve_request(args, c);
  const Branch parent =
      app::curve_branch(r, c, c.source(r.branch.start, r.branch.initial), nullptr);
  const BifurcationCurve curve = app::follow_curve(
      r, c.system(), parent, app::find_event(parent, r.event, "--event"), {}, &c.describer());
  ASSERT_GT(curve.points.size(), 1u);
  app::write_curve_json(r, curve, c, 0.0);
  std::vector<std::string> argv = {"curve", kRow2};
  argv.insert(argv.end(), words.begin(), words.end());
  argv.insert(argv.end(), {"--json", path("program.json")});
  ASSERT_EQ(program(argv), 0) << file_text(path("program.log"));
  EXPECT_EQ(without_times(path("library.json")), without_times(path("program.json")));
}

TEST_F(Requests, EquilibriaAreTheProgramsToTheLastDigit) {
  const app::Arguments args =
      typed("equilibria", kRow2,
            {text("--start", "in-phase"), text("--param", "s"), number("--from", 1e-8),
             number("--to", 0), text("--json", path("library.json"))});
  const app::LoadedSystem c = app::load_system(args);
  const app::EquilibriaRequest r = app::equilibria_request(args, c);
  const EquilibriumBranch branch = app::run_equilibria(r, c.system(), {});
  ASSERT_TRUE(branch.started());
  app::write_equilibria_json(r, branch, c, 0.0);
  ASSERT_EQ(program({"equilibria", kRow2, "--start", "in-phase", "--param", "s", "--from", "1e-8",
                     "--to", "0", "--json", path("program.json")}),
            0);
  EXPECT_EQ(without_times(path("library.json")), without_times(path("program.json")));
}

TEST_F(Requests, SimulationAndFitAreTheProgramsToTheLastDigit) {
  // A recording of one metronome (Table I's d and s), then d and s fitted to it from 20% off.
  app::SimulationRun simulation =
      app::prepare_simulation(typed("simulate", kSingle,
                                    {text("--start", "swing"), number("--t-end", 4),
                                     number("--dt", 0.05), text("--out", path("library.csv"))}));
  app::run_simulation(simulation, {});
  ASSERT_TRUE(simulation.failure.empty());
  ASSERT_EQ(program({"simulate", kSingle, "--start", "swing", "--t-end", "4", "--dt", "0.05",
                     "--out", path("program.csv")}),
            0);
  EXPECT_EQ(file_text(path("library.csv")), file_text(path("program.csv")));

  const app::FitSetup setup = app::fit_setup(typed(
      "fit", kSingle,
      {text("--data", path("program.csv")), text("--free", "d,s"), assignment("--set", "d", 2e-6),
       assignment("--set", "s", 5.4e-5), text("--json", path("library.json"))}));
  const app::FitRun run = app::run_fit(setup);
  ASSERT_TRUE(run.result.converged);
  app::write_fit_json(path("library.json"), setup, run, "", "", 0.0);
  ASSERT_EQ(program({"fit", kSingle, "--data", path("program.csv"), "--free", "d,s", "--set",
                     "d=2e-6", "--set", "s=5.4e-5", "--json", path("program.json")}),
            0)
      << file_text(path("program.log"));
  EXPECT_EQ(without_times(path("library.json")), without_times(path("program.json")));
}

TEST_F(Requests, StudyIsTheProgramsToTheLastDigit) {
  std::ofstream(path("small.toml"))
      << "title = \"small\"\ncase = \"" + kRow2 +
             "\"\nparams = \"table2\"\nparameter = \"k\"\naxis = \"phase\"\n\n"
             "[[branches]]\nname = \"anti-phase\"\nstart = \"anti-phase\"\nfrom = 44.0\n"
             "to = 50.0\n";
  app::StudyRun run = app::study_run(typed(
      "study", path("small.toml"), {text("--out", path("library")), text("--accuracy", "fast")}));
  app::run_study_branches(run, nullptr);
  ASSERT_TRUE(run.errors.front().empty()) << run.errors.front();
  app::write_study_json(run, 0.0);
  ASSERT_EQ(program({"study", path("small.toml"), "--out", path("program"), "--accuracy", "fast"}),
            0)
      << file_text(path("program.log"));
  nlohmann::json library = without_times(path("library/small.json"));
  nlohmann::json program_json = without_times(path("program/small.json"));
  EXPECT_EQ(library, program_json);
  EXPECT_EQ(file_text(path("library/small-anti-phase.csv")),
            file_text(path("program/small-anti-phase.csv")));
}

TEST_F(Requests, MapIsTheProgramsToTheLastDigit) {
  std::ofstream(path("small_map.toml"))
      << "title = \"small\"\ncase = \"" + kRow2 +
             "\"\nparams = \"table2\"\n\n[first]\nparameter = \"k\"\nfrom = 40.0\nto = 55.0\n"
             "points = 4\n\n[second]\nparameter = \"c\"\nfrom = 0.0\nto = 0.05\npoints = 3\n\n"
             "[[orbits]]\nname = \"anti-phase\"\nstart = \"anti-phase\"\n";
  app::MapRequest request;
  request.path = path("small_map.toml");
  request.out = path("library");
  request.accuracy = Accuracy::Fast;
  app::MapRun run = app::prepare_map(request);
  app::run_map(run, nullptr, {});
  ASSERT_TRUE(run.results.front().error.empty()) << run.results.front().error;
  app::write_map(run, 0.0);
  ASSERT_EQ(
      program({"map", path("small_map.toml"), "--out", path("program"), "--accuracy", "fast"}), 0)
      << file_text(path("program.log"));
  EXPECT_EQ(without_times(path("library/small_map.json")),
            without_times(path("program/small_map.json")));
}

TEST_F(Requests, BasinsAndSweepAreTheProgramsToTheLastDigit) {
  // Basins: 2 grid points, 3 starts each, 20 s runs.
  const auto basins =
      app::run_basins_here(typed("basins", kRow2,
                                 {text("--grid", "k=45:55:2"), integer("--starts", 3),
                                  number("--t-end", 20), text("--out", path("library"))}),
                           nullptr);
  ASSERT_FALSE(basins.interrupted);
  ASSERT_EQ(program({"basins", kRow2, "--grid", "k=45:55:2", "--starts", "3", "--t-end", "20",
                     "--out", path("program"), "--quiet"}),
            0)
      << file_text(path("program.log"));
  for (const char* file : {"basins_runs.csv", "basins_shares.csv"})
    EXPECT_EQ(file_text(path("library/") + file), file_text(path("program/") + file)) << file;
  EXPECT_EQ(without_times(path("library/basins.json")), without_times(path("program/basins.json")));

  // Sweep: the anti-phase orbit at three damping values.
  const auto sweep =
      app::run_sweep_here(typed("sweep", kRow2,
                                {text("--start", "anti-phase"), text("--over", "c=0:0.1:3"),
                                 text("--out", path("sweep_library"))}),
                          nullptr);
  ASSERT_FALSE(sweep.interrupted);
  ASSERT_EQ(program({"sweep", kRow2, "--start", "anti-phase", "--over", "c=0:0.1:3", "--out",
                     path("sweep_program"), "--quiet"}),
            0)
      << file_text(path("program.log"));
  EXPECT_EQ(file_text(path("sweep_library/sweep_orbits.csv")),
            file_text(path("sweep_program/sweep_orbits.csv")));
  EXPECT_EQ(without_times(path("sweep_library/sweep.json")),
            without_times(path("sweep_program/sweep.json")));
}

}  // namespace
}  // namespace sympathy
