#include "cases/cli/common.hpp"

#include "sympathy/core/csv.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <utility>

namespace sympathy::cli {

std::vector<OptionSpec> case_options() {
  return {
      {"--params", "NAME", false, "named parameter set of the case (default: the file's)"},
      {"--set", "KEY=VALUE", true, "set a parameter of the case to a value"},
  };
}

std::vector<OptionSpec> integrator_options() {
  return {
      {"--rtol", "R", false,
       "relative tolerance of the integrator (default: 5e-12 for orbits, branches and curves, the "
       "--accuracy preset's; 1e-8 for simulations; 1e-9 for fits)"},
      {"--atol", "A", false,
       "absolute tolerance of the integrator (default: 5e-14 for orbits, branches and curves, the "
       "--accuracy preset's; 1e-10 for simulations; 1e-11 for fits)"},
      {"--method", "bdf|adams|erk", false,
       "integration method: CVODES's BDF or Adams, or ARKODE's explicit Runge-Kutta "
       "(Dormand-Prince 5(4); with it the sensitivities are augmented) (default: adams for orbits, "
       "branches and curves, the --accuracy preset's, switched to bdf where the start measures "
       "stiff; bdf for simulations and fits; given, it is used whatever the stiffness)"},
      {"--sensitivities", "forward|augmented", false,
       "how the monodromy is integrated: CVODES's forward-sensitivity module, or the variational "
       "equations appended to the state (default: augmented for orbits, branches and curves, the "
       "--accuracy preset's; forward for fits)"},
      {"--linear-solver", "dense|klu|structured", false,
       "linear solver of the BDF Newton iteration (default: structured, sparse plus low rank, for "
       "more than 3 metronomes; else dense)"},
  };
}

void require_differentiable(const OdeSystem& system, const std::string& case_path,
                            const std::string& what) {
  if (system.differentiable()) return;
  throw InputError(case_path +
                   ": key 'escapement': the impulsive escapement (eq. 2) switches "
                   "discontinuously, and " +
                   what +
                   " needs the flow's sensitivities (monodromy matrices); expected escapement = "
                   "\"half\" or \"double\" (simulate runs the impulsive one)");
}

LoadedCase load_case(const Arguments& args) {
  return load_case(args.positional(0), args.text("--params", ""), args.assignments("--set"));
}

LoadedCase load_case(const std::string& path, const std::string& params,
                     const std::vector<Assignment>& sets) {
  LoadedCase c{CaseFile::load(path), "", {}};
  c.params = params.empty() ? c.file.default_parameter_set() : params;
  c.spec = c.file.spec(c.params, sets);
  return c;
}

OptionSpec accuracy_option() {
  return {"--accuracy", "fast|default|high", false,
          "integrator preset: fast = explicit Runge-Kutta at rtol 1e-8 and coarser branch steps, "
          "located points within 4e-7; default = Adams at rtol 5e-12, located points within "
          "1e-8; high = tighter (default: default; where a command takes --rtol, --method or "
          "--sensitivities, they override it)"};
}

Accuracy parse_accuracy(const std::string& text, const std::string& where) {
  if (auto a = accuracy_named(text)) return *a;
  throw InputError(where + " " + text + ": expected fast, default or high");
}

Accuracy accuracy(const Arguments& args) {
  const auto text = args.value("--accuracy");
  return text ? parse_accuracy(*text, "--accuracy") : Accuracy::Default;
}

FlowOptions flow_options(const Arguments& args, FlowOptions o) {
  o.rtol = args.number("--rtol", o.rtol);
  o.atol = args.number("--atol", o.atol);
  const char* given = o.method == Method::BDF ? "bdf" : o.method == Method::Adams ? "adams" : "erk";
  const std::string method = args.text("--method", given);
  if (method == "bdf") {
    o.method = Method::BDF;
    o.nonlinear_solver = NonlinearSolver::Newton;
  } else if (method == "adams") {
    o.method = Method::Adams;
    o.nonlinear_solver = NonlinearSolver::FixedPoint;
  } else if (method == "erk") {
    o.method = Method::ERK;
    o.sensitivities = Sensitivities::Augmented;  // an explicit method has no sensitivity module
  } else {
    throw InputError("--method " + method + ": expected bdf, adams or erk");
  }
  if (auto sensitivities = args.value("--sensitivities")) {
    if (*sensitivities == "forward")
      o.sensitivities = Sensitivities::ForwardModule;
    else if (*sensitivities == "augmented")
      o.sensitivities = Sensitivities::Augmented;
    else
      throw InputError("--sensitivities " + *sensitivities + ": expected forward or augmented");
  }
  check_options(o.validate(), "");
  if (!args.has("--linear-solver")) return o;  // as given (by default the flow's own choice)
  const std::string solver = args.text("--linear-solver", "");
  if (solver == "dense")
    o.linear_solver = LinearSolver::Dense;
  else if (solver == "klu")
    o.linear_solver = LinearSolver::KLU;
  else if (solver == "structured")
    o.linear_solver = LinearSolver::Structured;
  else
    throw InputError("--linear-solver " + solver + ": expected dense, klu or structured");
  return o;
}

std::string table_number(double v, const char* format) {
  if (!std::isfinite(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

OptionSpec segment_threads_option() {
  return {"--threads", "N", false,
          "threads integrating the shooting segments side by side (default: one per core; the "
          "result is the same for any number)"};
}

int segment_threads(const Arguments& args) {
  // Checked with the rest by ShootingOptions::validate (check_options names it --threads).
  if (args.has("--threads")) return args.integer("--threads", 1);
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 256);
}

void shooting_flow_options(const Arguments& args, OrbitOptions& o) {
  o.shooting.flow = flow_options(args, o.shooting.flow);
  o.transient_flow.linear_solver = o.shooting.flow.linear_solver;
  if (args.has("--method")) o.switch_when_stiff = false;  // the method asked for, stiff or not
}

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  if (g_interrupted.exchange(true)) std::_Exit(130);
}

// A file's identity: its device and inode where it exists, so that every spelling of it (a
// relative or absolute path, a symbolic link, a hard link) is the same file; a file that does
// not exist yet by its normalized absolute path (it cannot be a link to anything yet).
struct FileIdentity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  std::string path;
  // Equal for the same file, whatever its spelling.
  std::string key() const {
    return exists ? "file " + std::to_string(device) + ":" + std::to_string(inode) : "path " + path;
  }
};

FileIdentity identity(const std::string& path) {
  FileIdentity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
    return id;
  }
  std::error_code ec;
  const auto canonical = std::filesystem::weakly_canonical(path, ec);
  id.path = ec ? std::filesystem::absolute(path).lexically_normal().string() : canonical.string();
  return id;
}

}  // namespace

extern "C" void on_interrupt_exit(int) {
  // Async-signal-safe: write(2) and _exit alone.
  static const char message[] = "sympathy: interrupted: stopped, no file written (exit 6)\n";
  const ssize_t ignored = ::write(2, message, sizeof message - 1);
  static_cast<void>(ignored);
  ::_exit(6);
}

void exit_on_interrupt() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, on_interrupt_exit);
}

const std::atomic<bool>* interrupt_flag() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, on_interrupt);
  return &g_interrupted;
}

void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outputs,
                            const std::vector<std::pair<std::string, std::string>>& inputs) {
  // Each file's identity once, looked up in a map: a study of 1,600 branches (4,800 outputs)
  // compared every pair, each comparison resolving both paths, and waited 108 s before its
  // first file.
  std::map<std::string, const std::string*> input_of;  // identity -> the input's name
  for (const auto& [input_name, input] : inputs)
    if (!input.empty()) input_of.emplace(identity(input).key(), &input_name);
  std::map<std::string, const std::string*> output_of;  // identity -> the output's option
  for (const auto& [option, path] : outputs) {
    if (path.empty()) continue;
    const std::string key = identity(path).key();
    if (const auto it = input_of.find(key); it != input_of.end())
      throw InputError(option + " " + path + ": is the " + *it->second +
                       "; expected an output that does not replace an input");
    if (const auto [it, added] = output_of.emplace(key, &option); !added)
      throw InputError(option + " " + path + ": the same file as " + *it->second +
                       "; expected a different file for each output");
  }
}

std::vector<std::pair<std::string, std::string>> with(
    std::vector<std::pair<std::string, std::string>> files,
    std::pair<std::string, std::string> more) {
  files.push_back(std::move(more));
  return files;
}

void check_parameter_range(const ModelSpec& spec, const std::string& parameter,
                           const std::vector<double>& values, const std::string& where) {
  for (double v : values) {
    ModelSpec at = spec;
    at.set(parameter, v);
    const auto problems = at.problems();
    if (!problems.empty())
      throw InputError(where + parameter + " = " + format_double(v) + " is outside the model's " +
                       "domain: " + problems.front().first + " must be " + problems.front().second);
  }
}

void check_options(const OptionCheck& problem, const std::string& where) {
  if (!problem) return;
  // The command line's names of the options fields it sets (the study file's keys are the same
  // without the dashes, where = "FILE: branches[i]."); a field it does not set keeps its own name.
  static const std::pair<const char*, const char*> names[] = {
      {"initial_step", "step"},
      {"max_step", "max-step"},
      {"max_points", "max-points"},
      {"user_points", "user-points"},
      {"orbit.transient", "transient"},
      {"transient", "transient"},
      {"orbit.shooting.segments", "segments"},
      {"shooting.segments", "segments"},
      {"orbit.shooting.threads", "threads"},
      {"shooting.threads", "threads"},
      {"rtol", "rtol"},
      {"atol", "atol"},
      {"sensitivities", "sensitivities"},
      {"method", "method"},
      {"orbit.shooting.flow.rtol", "rtol"},
      {"orbit.shooting.flow.atol", "atol"},
      {"shooting.flow.rtol", "rtol"},
      {"shooting.flow.atol", "atol"}};
  std::string name = problem->field;
  for (const auto& [field, option] : names)
    if (name == field) {
      name = option;
      break;
    }
  if (where.empty()) {
    throw InputError("--" + name + ": expected " + problem->expected);
  }
  std::replace(name.begin(), name.end(), '-', '_');
  throw InputError(where + name + ": expected " + problem->expected);
}

}  // namespace sympathy::cli
