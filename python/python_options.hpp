// Keyword arguments of a Python call read as the options of the command of the same name: the
// module has no option table, defaults or checks of its own. `case.continue_branch(param="k",
// from_=1, to=100, max_step=0.05)` is `sympathy continue CASE --param k --from 1 --to 100
// --max-step 0.05`, read by the same Arguments and checked by the same code.
#pragma once

#include <string>
#include <vector>

#include <pybind11/pybind11.h>

#include "cases/cli/arguments.hpp"

namespace sympathy::python {

namespace py = pybind11;

// The case a call runs on: its file, parameter set ("" for the file's default) and --set values
// (KEY=VALUE), given before the call's own options.
struct CaseLine {
  std::string path;
  std::string params;
  std::vector<std::string> sets;
  std::vector<std::string> arguments() const;
};

// `command`'s arguments: the case's, then each keyword as its option (from_ or from -> --from,
// max_step -> --max-step). A flag's True gives it and False leaves it out; None leaves any option
// out; a dict gives KEY=VALUE once per item (set, initial); a list or tuple its items joined by
// commas (user_points); a number its Python repr, which reads back as the same double. A keyword
// that names no option of the command, or one of `reserved` (set on the Case instead), raises
// TypeError as Python does for an unexpected keyword, with the keywords the call takes.
cli::Arguments command_arguments(const std::string& command, const CaseLine& line,
                                 const py::kwargs& kwargs,
                                 const std::vector<cli::OptionSpec>& options,
                                 const std::vector<std::string>& reserved);

}  // namespace sympathy::python
