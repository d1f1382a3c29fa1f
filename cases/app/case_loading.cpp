#include "cases/app/case_loading.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <string>
#include <utility>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "sympathy/core/hybrid_system.hpp"

namespace sympathy::app {

namespace {

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

LoadedCase load_case(const std::string& path, const std::string& params,
                     const std::vector<Assignment>& sets) {
  LoadedCase c{CaseFile::load(path), "", {}};
  c.params = params.empty() ? c.file.default_parameter_set() : params;
  c.spec = c.file.spec(c.params, sets);
  return c;
}

void require_differentiable(const OdeSystem& system, const std::string& switching,
                            const std::string& what, const std::string& expected) {
  // A piecewise-smooth model's orbit is exact (its monodromy crosses the switching surfaces with
  // saltation matrices), and so are branches, sweeps of branches, curves and maps of them, which
  // end where an orbit grazes a surface (grazing.hpp; sliding, two solutions and chattering are
  // refused by the flow). Equilibria lie on its surfaces, where its field has no derivative.
  const bool hybrid_orbits = (what == "orbit" || what == "continue" || what == "curve" ||
                              what == "sweep" || what == "a branch" || what == "a map") &&
                             dynamic_cast<const HybridSystem*>(&system);
  if (system.differentiable() && (system.switching_count() == 0 || hybrid_orbits)) return;
  throw InputError(switching + " switches discontinuously, and " + what +
                   " is not built for it (orbits, branches, sweeps, curves and maps are); "
                   "expected " +
                   expected);
}

Accuracy parse_accuracy(const std::string& text, const std::string& where) {
  if (auto a = accuracy_named(text)) return *a;
  throw InputError(where + " " + text + ": expected fast, default or high");
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

}  // namespace sympathy::app
