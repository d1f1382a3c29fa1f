// Loading a case file and the checks every request makes before any work, for the command line
// and Python alike: the case with its parameter set and overrides, the model's domain, outputs
// that never replace an input, an accuracy preset's name, and an option problem named as the
// command line or a study file names it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "sympathy/cases/case_file.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/names.hpp"
#include "sympathy/continuation/accuracy.hpp"
#include "sympathy/core/ode_system.hpp"
#include "sympathy/core/option_check.hpp"

namespace sympathy::app {

// A metronome case file loaded: the file, the parameter set applied, the model it specifies.
struct LoadedCase {
  CaseFile file;
  std::string params;  // the parameter set applied ("" if none)
  ModelSpec spec;
};

// Throws InputError "WHERE TEXT: expected fast, default or high" unless TEXT names a preset.
Accuracy parse_accuracy(const std::string& text, const std::string& where);
// InputError unless `what` ("orbit", "continue", "equilibria", "a map", ...) is built for the
// model: a smooth one, or a piecewise-smooth one (a HybridSystem) for its orbits and everything
// built on them (branches, sweeps, curves, maps), not for equilibria, which lie on its surfaces.
// `switching` names the case file and what switches ("FILE: key 'escapement': the impulsive
// escapement (eq. 2)"), `expected` what would do. Before any work.
void require_differentiable(const OdeSystem& system, const std::string& switching,
                            const std::string& what, const std::string& expected);
// The case file at `path` with parameter set `params` ("" for the file's default) and `sets`
// (name = value overrides) on top.
LoadedCase load_case(const std::string& path, const std::string& params,
                     const std::vector<Assignment>& sets);
// Throws the InputError of an options problem (the engine's validate()), named as the command
// line names it ("--step: expected ...", where = "") or as a study file does (where =
// "FILE: branches[2]." gives "FILE: branches[2].step: expected ...").
void check_options(const OptionCheck& problem, const std::string& where);

// Throws InputError (prefixed by `where`) unless the model is physically meaningful with
// `parameter` at every one of `values` (ModelSpec::problems: masses and lengths positive,
// damping and stiffness non-negative, ...), so that a range reaching out of the domain is refused
// before any work instead of failing later as an integration error.
void check_parameter_range(const ModelSpec& spec, const std::string& parameter,
                           const std::vector<double>& values, const std::string& where);

// Throws InputError when two of `paths` (option, path) name the same file, or one of them names
// an input (option, path) such as the case file: an output must never replace an input or
// another output of the same run. Files are compared by device and inode, so a hard or symbolic
// link to an input is that input. Empty paths are ignored.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                            const std::vector<std::pair<std::string, std::string>>& inputs);

// `files` with `more` appended (for check_distinct_outputs' lists of inputs).
std::vector<std::pair<std::string, std::string>> with(
    std::vector<std::pair<std::string, std::string>> files,
    std::pair<std::string, std::string> more);

}  // namespace sympathy::app
