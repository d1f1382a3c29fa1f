// The project's case files and metronome states, for tests of the model and the engine on them.
#pragma once

#include <random>
#include <string>

#include <Eigen/Dense>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/branch_run.hpp"

namespace sympathy::testing {

// cases/NAME.toml in the source tree (NAME may hold a folder: "many/many16").
inline std::string case_path(const std::string& name) {
  return std::string(SYMPATHY_SOURCE_DIR) + "/cases/" + name + ".toml";
}

// cases/examples/NAME.toml: the examples of equation case files.
inline std::string example_path(const std::string& name) {
  return case_path("examples/" + name);
}

// A case's parameter set ("" for the file's default) with the given escapement.
inline ModelSpec load_spec(const std::string& name, const std::string& params = "",
                           Escapement escapement = Escapement::Half) {
  ModelSpec spec = CaseFile::load(case_path(name)).spec(params);
  spec.escapement = escapement;
  return spec;
}

// Random states of the size of real swings: angles up to 0.8 rad, velocities up to 4 rad/s,
// platform displacements of millimetres.
inline Eigen::VectorXd random_state(const MetronomeModel& model, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd z(model.dimension());
  const int D = model.platform_directions();
  const int m = D + model.metronome_count();
  for (int a = 0; a < D; ++a) {
    z[a] = 2e-3 * u(rng);
    z[m + a] = 2e-2 * u(rng);
  }
  for (int i = 0; i < model.metronome_count(); ++i) {
    z[D + i] = 0.8 * u(rng);
    z[m + D + i] = 4.0 * u(rng);
  }
  return z;
}

// A branch of a case file's named start in `parameter`, from the model's own value of it to `to`,
// in the subspace the start declares.
inline BranchProblem branch_problem(const CaseFile& file, const MetronomeModel& model,
                                    const std::string& start_name, const std::string& parameter,
                                    double to) {
  const StartSpec& start = file.start(start_name);
  BranchProblem problem;
  problem.parameter = model.parameter_index(parameter);
  problem.values = model.default_parameters();
  problem.from = model.parameter(problem.values, problem.parameter);
  problem.to = to;
  problem.start_state = file.initial_state(&start);
  problem.subspace = file.invariant_subspace(start, model);
  return problem;
}

}  // namespace sympathy::testing
