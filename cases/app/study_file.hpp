// Study files (cases/figures/*.toml): the branches that make one figure, next to a case. Read by
// `sympathy study` (cases/cli/study.cpp) and by the fuzz target tests/fuzz/study_file_fuzz.cpp.
#pragma once

#include <string>
#include <vector>

#include "cases/app/branch_run.hpp"
#include "cases/app/saved_start.hpp"

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
};

struct Study {
  std::string path, name, title, case_path, params, parameter, axis;
  Accuracy accuracy = Accuracy::Default;  // the file's `accuracy`, applied to every branch
  std::vector<StudyBranch> branches;
  // Parameter sets of the case whose value of `parameter` the figure marks (the paper's Fig. 9:
  // the platform's stiffness before and after the fit, Tables II and III).
  std::vector<std::string> marks;
};

// Reads and checks a study file (its keys, types and each branch's options; not yet its case);
// throws InputError naming the file, the line and the key.
Study load_study(const std::string& path);

}  // namespace sympathy::app
