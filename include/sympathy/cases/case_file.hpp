// Case files (cases/*.toml): a metronome-platform system, its named parameter sets and its
// named starts. The format is documented in README.md ("Case files").
//
// Everything is validated on load and when a parameter set and --set assignments are applied,
// before any computation: an error names the file and line (or the command-line argument), the
// key, and what was expected.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>
#include <Eigen/Dense>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/toml_reader.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/invariant_subspace.hpp"

namespace sympathy {

// One "KEY=VALUE" given on the command line (or by a study), with where it came from.
struct Assignment {
  std::string key;
  double value = 0.0;
  std::string source;  // e.g. "--set M=0.2"
};
// Parses "KEY=VALUE" given to `option`; throws InputError naming the option.
Assignment parse_assignment(const std::string& text, const std::string& option);

// A linear relation kept by an invariant subspace: component = sign * other, or component = 0.
struct Relation {
  std::string component;
  std::string other;  // empty for "component = 0"
  double sign = 1.0;
};

struct StartSpec {
  std::string name;
  std::vector<std::pair<std::string, double>> values;  // state name -> value; others are 0
  std::vector<Relation> invariant;                     // positions; velocities follow
  std::string source;                                  // "FILE:LINE"
};

struct ParameterSet {
  std::string name;
  struct Entry {
    std::string key;
    double value;
    int line;
  };
  std::vector<Entry> entries;
  int line = 0;
};

class CaseFile {
 public:
  // Reads and checks a case file; throws InputError.
  static CaseFile load(const std::string& path);

  const std::string& path() const { return path_; }
  const std::string& name() const { return name_; }
  const std::string& description() const { return description_; }
  const std::string& default_parameter_set() const { return default_params_; }
  std::vector<std::string> parameter_set_names() const;
  std::vector<std::string> start_names() const;
  std::vector<std::string> state_names() const;

  // The model with parameter set `params` (empty: the file's default, if any) and then the
  // assignments applied in order; every value checked. Throws InputError.
  ModelSpec spec(const std::string& params = "", const std::vector<Assignment>& sets = {}) const;

  // A named start; throws InputError listing the known ones.
  const StartSpec& start(const std::string& name) const;
  // The invariant subspace a start declares, on positions and the matching velocities;
  // throws InputError if `system` does not keep it invariant.
  InvariantSubspace invariant_subspace(const StartSpec& start, const OdeSystem& system) const;
  // The initial state of a start, with assignments VAR=VALUE on top (state names).
  Eigen::VectorXd initial_state(const StartSpec* start,
                                const std::vector<Assignment>& initial = {}) const;

 private:
  std::string path_;
  std::string name_;
  std::string description_;
  std::string default_params_;
  ModelSpec base_;
  // Where each value of base_ came from, as (parameter name, "FILE:LINE: key"), in order.
  std::vector<std::pair<std::string, std::string>> provenance_;
  std::vector<ParameterSet> parameter_sets_;
  std::vector<StartSpec> starts_;
};

}  // namespace sympathy
