#include "cases/cli/case_arguments.hpp"

#include <string>

#include "cases/cli/start_data.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy::cli {

LoadedSystem load_system(const Arguments& args) {
  return LoadedSystem(args.positional(0), args.text("--params", ""), args.assignments("--set"),
                      start_data_path(args), args.command());
}

ParameterWindow parameter_window(const Arguments& args, const LoadedSystem& c) {
  for (const char* required : {"--param", "--from", "--to"})
    if (!args.has(required)) throw InputError(std::string(required) + " is required");
  ParameterWindow w;
  w.parameter = *args.value("--param");
  c.require_parameter("--param", w.parameter);
  w.from = args.number("--from", 0.0);
  w.to = args.number("--to", 0.0);
  if (w.from == w.to) throw InputError("--from and --to: expected different values");
  if (args.has("--at")) w.at = args.number("--at", 0.0);
  return w;
}

}  // namespace sympathy::cli
