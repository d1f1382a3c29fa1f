#include "python_options.hpp"

#include <algorithm>

namespace sympathy::python {

std::vector<std::string> CaseLine::arguments() const {
  std::vector<std::string> a{path};
  // OPTION=VALUE, one argument: a value that begins with "-" is never read as an option.
  if (!params.empty()) a.push_back("--params=" + params);
  for (const auto& s : sets) a.push_back("--set=" + s);
  return a;
}

namespace {

// A value as the command line writes it: Python's own repr for numbers (17 significant digits
// where needed, so that the option reads back as the same double), str() for the rest.
std::string text_of(const py::handle& value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::hasattr(value, "__index__"))
    return py::str(py::int_(py::reinterpret_borrow<py::object>(value)));
  if (py::isinstance<py::float_>(value) || py::hasattr(value, "__float__"))
    return py::repr(py::float_(py::reinterpret_borrow<py::object>(value)));
  return py::str(value);
}

std::string keyword_of(const std::string& option) {
  std::string k = option.substr(2);
  std::replace(k.begin(), k.end(), '-', '_');
  return k;
}

}  // namespace

cli::Arguments command_arguments(const std::string& command, const CaseLine& line,
                                 const py::kwargs& kwargs,
                                 const std::vector<cli::OptionSpec>& options,
                                 const std::vector<std::string>& reserved) {
  std::vector<std::string> argv = line.arguments();
  for (const auto& [key, value] : kwargs) {
    std::string name = key.cast<std::string>();
    // from_: `from` is a Python keyword.
    if (!name.empty() && name.back() == '_') name.pop_back();
    std::string option = "--" + name;
    std::replace(option.begin(), option.end(), '_', '-');
    const auto spec = std::find_if(options.begin(), options.end(),
                                   [&](const cli::OptionSpec& s) { return s.name == option; });
    if (spec == options.end() ||
        std::find(reserved.begin(), reserved.end(), name) != reserved.end()) {
      std::string known;
      for (const auto& s : options) {
        const std::string k = keyword_of(s.name);
        if (std::find(reserved.begin(), reserved.end(), k) != reserved.end()) continue;
        known += (known.empty() ? "" : ", ") + (k == "from" ? std::string("from_") : k);
      }
      throw py::type_error(command + "() got an unexpected keyword argument '" +
                           key.cast<std::string>() + "'; expected one of: " + known);
    }
    if (value.is_none()) continue;
    if (spec->value.empty()) {  // a flag
      if (!py::isinstance<py::bool_>(value))
        throw py::type_error(command + "(): " + name + " is a flag; expected True or False");
      if (value.cast<bool>()) argv.push_back(option);
      continue;
    }
    if (py::isinstance<py::dict>(value)) {
      for (const auto& [k, v] : value.cast<py::dict>())
        argv.push_back(option + "=" + py::str(k).cast<std::string>() + "=" + text_of(v));
      continue;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
      std::string joined;
      for (const auto& item : value) joined += (joined.empty() ? "" : ",") + text_of(item);
      argv.push_back(option + "=" + joined);
      continue;
    }
    argv.push_back(option + "=" + text_of(value));
  }
  return cli::Arguments(command, argv, options, {"CASE"});
}

}  // namespace sympathy::python
