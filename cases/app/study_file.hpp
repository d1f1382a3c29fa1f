// Study files (cases/figures/*.toml): the branches that make one figure, next to a case. Read by
// `sympathy study` (cases/cli/study.cpp) and by the fuzz target tests/fuzz/study_file_fuzz.cpp.
#pragma once

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cases/app/branch_run.hpp"
#include "cases/app/saved_start.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/toml_reader.hpp"
#include "sympathy/continuation/attractor_run.hpp"
#include "sympathy/continuation/equilibrium_branch.hpp"

namespace sympathy::app {

struct StudyBranch {
  std::string name;
  // switch_at = "PARENT:BP1": the branch born at that event of the study's branch PARENT (which
  // is computed first and not again); empty when the branch switches at an event of its own
  // parent run (switch_at = "BP1") or not at all.
  std::string parent;
  BranchRequest request;
  std::vector<Assignment> sets;  // on top of the study's parameter set
  // `user_value` and `stop_at` (tables of QUANTITY = VALUE, as continue's --user-value and
  // --stop-at): read against the case's states by the study (study_run).
  std::vector<Assignment> user_values, stops;
  // `start_data`: a recorded period to start from instead of `start` (relative to the study
  // file; read by the study against its case's states).
  std::string start_data;
  // `transient` given: a forced system's branch integrates it too (by default it starts with
  // Newton at once, as continue's).
  bool transient_given = false;
  // `parent` and `from_point`: the branch starts from a point or event an earlier run saved
  // (continue's --parent FILE --from-point POINT; the file relative to the study file).
  std::optional<SavedStart> saved;
  // switch_at = "NAME:HB1" with NAME an [[equilibria]] entry: the family born at that entry's
  // Hopf point (request.switch_at "HB1"; the entry computed first).
  std::string equilibria_parent;
};

// An [[equilibria]] table: one `equilibria` run in the study's parameter (cases/app/requests.hpp),
// read by study_equilibria_file.cpp.
struct StudyEquilibria {
  std::string name;
  std::string start;  // "" for an equation case file's [states] (a metronome case needs one)
  double from = 0.0, to = 0.0;
  std::optional<double> at;
  std::vector<Assignment> sets, initial;
  std::optional<SavedStart> saved;  // `parent` and `from_point`, as equilibria --from-point
  // switch_at = "BPn": n, the branch born at the n-th BP of the entry's own run over its window;
  // with `parent` (switch_at = "NAME:BPn") at that BP of the study's entry NAME, listed before.
  int switch_at = 0;
  std::string parent;
  EquilibriumOptions options;  // max_points, step, max_step, user_points; bounds from from, to
};

// The [basins] table (study_basins_file.cpp): basin shares walked along the study's parameter
// (continuation/basin_walk.hpp), their attractors named by the study's branches.
struct StudyBasins {
  double from = 0.0, to = 0.0;
  int count = 2;
  int starts = 100;
  std::uint64_t seed = 1;
  int threads = 0;    // 0: one per core
  std::string start;  // the case's start the states outside `box` keep ("": an equation case
                      // file's [states])
  struct Range {
    std::string state;
    double lower = 0.0, upper = 0.0;
    std::string where;  // FILE:LINE, for the message that names a state the case lacks
  };
  std::vector<Range> box;  // the states drawn, each uniformly in its range
  AttractorRunOptions run;
  std::string where;                   // FILE:LINE of the table
  std::vector<double> values() const;  // count values from `from` to `to`
};

struct Study {
  std::string path, name, title, case_path, params, parameter, axis;
  Accuracy accuracy = Accuracy::Default;  // the file's `accuracy`, applied to every branch
  // A metronome case's escapement instead of its file's (`escapement`; the paper's Fig. 8 on its
  // own escapement beside the smoothed one); nullopt: the file's.
  std::optional<Escapement> escapement;
  std::vector<StudyBranch> branches;
  std::vector<StudyEquilibria> equilibria;  // computed before the branches that need them
  // The state plot_study draws the equilibria's diagram in (`equilibria_axis`; "" for the first).
  std::string equilibria_axis;
  // Parameter sets of the case whose value of `parameter` the figure marks (the paper's Fig. 9:
  // the platform's stiffness before and after the fit, Tables II and III).
  std::vector<std::string> marks;
  std::optional<StudyBasins> basins;
};

// Reads and checks a study file (its keys, types and each branch's and equilibria entry's
// options; not yet its case); throws InputError naming the file, the line and the key.
Study load_study(const std::string& path);

// The study's [[equilibria]] tables (`list`, the node of key "equilibria") into s.equilibria,
// checked as load_study checks branches; their names added to `names` (a name is unique across
// branches and equilibria: it names files).
// The study's [basins] table (`node`) into s.basins, every key checked (not yet its states).
void read_study_basins(const TomlReader& in, const toml::node& node, Study& s);

void read_study_equilibria(const TomlReader& in, const toml::node& list, Study& s,
                           std::set<std::string>& names);

}  // namespace sympathy::app
