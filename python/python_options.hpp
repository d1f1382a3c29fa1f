// Python's keyword arguments as a command's options, typed: the one option table
// (cases/app/option_table.hpp) less what a Case carries or Python has no use for, given to the
// package (python/sympathy/__init__.py) to build each function's signature and check each
// keyword's type, and the checked values read into the same Arguments the program reads, as
// values, not text (no argv strings).
#pragma once

#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "cases/app/arguments.hpp"
#include "cases/app/options.hpp"
#include "sympathy/cases/case_file.hpp"

namespace sympathy::python {

namespace py = pybind11;

// The case a call runs on: its file, parameter set ("" for the file's default) and values set on
// top of it.
struct CaseLine {
  std::string path;
  std::string params;
  std::vector<Assignment> sets;
};

// The commands Python runs, by the name of the command (simulate, orbit, continue, curve,
// equilibria, fit, study), and each one's options as keywords: the table's without those left
// out (--params, which the Case carries; outputs and printing options of the program's).
std::vector<std::string> python_commands();
std::vector<app::OptionSpec> python_options(const std::string& command);

// A command's keywords for the package: a list of dicts (keyword, option, kind, placeholder, help,
// repeatable, required, choices), in the table's order.
py::list option_table(const std::string& command);

// The arguments of `command` on `line` from the package's checked keywords (a dict: keyword ->
// value, typed by its kind: bool for a flag, int, float, a list of floats, a dict of floats for
// KEY=VALUE options, a list of str for a repeatable text option, str for the rest). Nothing
// numeric is read from text. InputError with
// keywords for options (as with_keywords) on any problem the checks find.
app::Arguments typed_arguments(const std::string& command, const CaseLine& line,
                               const py::dict& keywords);

// Runs f(), an InputError's message turned to the command's keywords ("--step" -> "step").
template <class F>
auto with_keywords(const std::string& command, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const InputError& e) {
    throw InputError(app::with_keywords(e.what(), python_options(command)));
  }
}

}  // namespace sympathy::python
