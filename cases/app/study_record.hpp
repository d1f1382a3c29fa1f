// The identity of a journaled study (basins, sweep), so that a journal is resumed only by the
// study that wrote it (issue 32: a basins journal resumed with another --set kept the old rows and
// computed the rest under the new parameters, exit 0, "complete": true).
//
// A record is written beside the journal (JOURNAL.study) before its first row: sympathy's
// version; every option as given except those that cannot change a result (threads, output
// directory, --resume, progress); and the SHA-256 of the content of every file the study reads
// (the case file, a plug-in's source, a study file, a recording), by content rather than by path,
// so that a study moved to another directory resumes. A resumed run's record must equal it, else
// InputError names the first difference. Options are compared as given: an option given with its
// default value differs from the option left out (the safe side: refused, never mixed).
#pragma once

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "cases/app/arguments.hpp"

namespace sympathy::app {

struct StudyRecord {
  // (what, value) in a canonical order: "sympathy", then options sorted by name (values of a
  // repeated option in the order given), then files.
  std::vector<std::pair<std::string, std::string>> entries;
  std::string text() const;
};

// The record of the study `args` asks for; `inputs` (what, path) the files it reads (empty paths
// skipped); `ignored` the options that do not change a result.
StudyRecord study_record(const Arguments& args,
                         const std::vector<std::pair<std::string, std::string>>& inputs,
                         const std::set<std::string>& ignored);

// A new journal (the file at `journal_path` does not exist yet): writes `record` to
// JOURNAL.study. A resumed one: reads JOURNAL.study and throws InputError naming the first
// difference, or that the record is missing (a journal of an earlier sympathy).
void check_or_write_study_record(const std::string& journal_path, const StudyRecord& record,
                                 bool resuming);

}  // namespace sympathy::app
