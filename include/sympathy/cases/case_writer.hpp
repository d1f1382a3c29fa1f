// Writing a copy of a case file with new parameter values in place (sympathy fit --out): the
// text is kept line for line, comments included; only the values change, each with a comment
// saying where it came from, and a header comment says what was done.
//
// Where a value goes: in place of the key that gives it (the entry of the parameter set in use,
// else platform.M, metronome.d, metronomes[2].d, g, the springs' kappa); failing that, a new
// entry in the set in use, in the metronome's own [[metronomes]] table, or a new set
// [params.fitted]. If the set is not the file's default, the copy's `default_params` names it,
// so that the copy runs unchanged with the new values. The copy is loaded back and each value
// checked before the function returns.
#pragma once

#include <string>
#include <vector>

#include "sympathy/cases/case_file.hpp"

namespace sympathy {

struct NewValue {
  std::string name;  // a parameter name of the case
  double value = 0.0;
  std::string note;  // the comment placed beside it, e.g. "fitted, standard error 3.1e-08"
};

// Writes the copy to `out_path`; `header` lines become comments at its top. Returns one line per
// edit ("metronome.d (line 20): 2.4e-06 -> 2.41e-06"). Throws InputError if the file cannot be
// written, std::runtime_error if the copy does not load back with the values (another key of
// the file overrides one).
std::vector<std::string> write_case_with_values(const CaseFile& file, const std::string& params,
                                                const std::vector<NewValue>& values,
                                                const std::vector<std::string>& header,
                                                const std::string& out_path);

}  // namespace sympathy
