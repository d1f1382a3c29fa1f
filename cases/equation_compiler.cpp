#include "sympathy/cases/equation_compiler.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sympathy/cases/equation_codegen.hpp"
#include "sympathy/cases/equation_toolchain.hpp"
#include "sympathy/cases/sha256.hpp"
#include "sympathy/core/binary_interface.hpp"
#include "sympathy/core/output_file.hpp"

extern char** environ;

namespace sympathy {

namespace {

namespace fs = std::filesystem;

// The flags of a Release build of sympathy's own code (CMAKE_CXX_FLAGS_RELEASE), so a generated
// system runs as fast as one compiled into sympathy. -fvisibility=hidden: the library exports
// its C factory only. Measured (bench (h), 2026-11-24): -O2 compiles a 900-term sum in 16 s
// instead of 32 s (-O1: 3.8 s) and small systems in the same 2-3 s (the headers dominate), with
// the same right-hand-side speed, but abc's Jacobian 1.2x the hand-written one's instead of
// 0.46x: -O3 kept.
const std::vector<std::string> kFlags{"-std=c++20", "-O3",     "-DNDEBUG",
                                      "-fPIC",      "-shared", "-fvisibility=hidden"};

std::optional<std::string> read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The include directory whose engine headers are those this build was compiled with:
// SYMPATHY_INCLUDE_DIR if set, else the source tree's, else the installed ones.
std::string engine_include_dir() {
  std::vector<std::string> candidates;
  if (const char* dir = std::getenv("SYMPATHY_INCLUDE_DIR"); dir && *dir)
    candidates.emplace_back(dir);
  candidates.emplace_back(toolchain::kBuildInclude);
  candidates.emplace_back(toolchain::kInstallInclude);
  std::string tried;
  for (const auto& dir : candidates) {
    std::string problem;
    for (const auto& header : toolchain::kEngineHeaders) {
      const auto text = read_file(fs::path(dir) / header.path);
      if (!text) {
        problem = "no " + std::string(header.path);
        break;
      }
      if (sha256_hex(*text) != header.sha256) {
        problem = std::string(header.path) + " differs from the one this sympathy was built with";
        break;
      }
    }
    if (problem.empty()) return dir;
    tried += "\n  " + dir + ": " + problem;
  }
  throw std::runtime_error(
      "equation case files need sympathy's headers, as this program was built with them, to "
      "compile a system; tried (set SYMPATHY_INCLUDE_DIR to choose):" +
      tried);
}

// The flags of every compile: kFlags, then the program's own (toolchain::kExtraFlags).
std::vector<std::string> compile_flags() {
  std::vector<std::string> flags = kFlags;
  for (const char* const* f = toolchain::kExtraFlags; *f != nullptr; ++f) flags.emplace_back(*f);
  return flags;
}

std::string cache_key(const std::string& source) {
  std::string identity = "sympathy-equations abi " + std::to_string(kEquationAbi) + "\n";
  identity += std::string("sympathy ") + toolchain::kVersion + "\n";
  identity +=
      std::string("compiler ") + toolchain::kCompiler + " (" + toolchain::kCompilerIdentity + ")\n";
  for (const auto& flag : compile_flags()) identity += flag + " ";
  identity += "\n";
  identity += std::string("binary interface ") + kBinaryInterface + "\n";
  for (const auto& header : toolchain::kEngineHeaders)
    identity += std::string(header.path) + " " + header.sha256 + "\n";
  return sha256_hex(identity + source);
}

std::string manifest_text(const std::string& key, const std::string& library_sha256) {
  return "sympathy-equations-cache 1\nkey " + key + "\nlibrary-sha256 " + library_sha256 + "\n";
}

// Runs `argv` (no shell), its output into `log`; returns its exit status (-1 if it could not
// start).
int run(const std::vector<std::string>& argv, const fs::path& log) {
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int started = posix_spawn(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (started != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Compiles `source` into the cache entry `key` (KEY.cpp, KEY.so, KEY.manifest) against the
// engine headers in `include`.
void compile(const fs::path& dir, const std::string& key, const std::string& source,
             const std::string& include, const std::string& what) {
  write_file_atomically((dir / (key + ".cpp")).string(), source);
  const std::string unique = key + "." + std::to_string(::getpid());
  const fs::path library = dir / (unique + ".so.tmp");
  const fs::path log = dir / (unique + ".log.tmp");
  std::vector<std::string> argv{toolchain::kCompiler};
  const auto flags = compile_flags();
  argv.insert(argv.end(), flags.begin(), flags.end());
  argv.insert(argv.end(), {"-DSYMPATHY_EQUATIONS_TAG=\"" + key + "\"", "-I" + include,
                           "-I" + std::string(toolchain::kEigenInclude), "-o", library.string(),
                           (dir / (key + ".cpp")).string()});
  const int status = run(argv, log);
  if (status != 0) {
    std::error_code ec;
    fs::rename(log, dir / (key + ".log"), ec);
    fs::remove(library, ec);
    std::string output = read_file(dir / (key + ".log")).value_or("");
    if (output.size() > 2000) output = output.substr(0, 2000) + "\n...";
    throw std::runtime_error(
        std::string(what) + " failed (" +
        (status < 0 ? "could not run " : "exit status " + std::to_string(status) + " of ") +
        toolchain::kCompiler + "); output in " + (dir / (key + ".log")).string() + ":\n" + output);
  }
  std::error_code ec;
  fs::remove(log, ec);
  const auto bytes = read_file(library);
  if (!bytes) throw std::runtime_error("cannot read the compiled library " + library.string());
  fs::rename(library, dir / (key + ".so"));  // atomic within the directory
  write_file_atomically((dir / (key + ".manifest")).string(),
                        manifest_text(key, sha256_hex(*bytes)));
}

// Why the entry `key` cannot be loaded, or "" if its manifest vouches for its library.
std::string entry_problem(const fs::path& dir, const std::string& key) {
  const auto manifest = read_file(dir / (key + ".manifest"));
  const auto library = read_file(dir / (key + ".so"));
  if (!manifest && !library) return "absent";
  if (!manifest) return "its manifest is missing";
  if (!library) return "its library is missing";
  if (*manifest != manifest_text(key, sha256_hex(*library)))
    return "its library does not match its manifest (corrupt or foreign)";
  return "";
}

struct Library {
  void* handle = nullptr;
  using Create = void* (*)(const char* const*, int, const char* const*, const double*, int);
  using Destroy = void (*)(void*);
  Create create = nullptr;
  Destroy destroy = nullptr;
};

// dlopen and the C interface's checks; nullopt (closed again) when the tag or ABI differ.
std::optional<Library> open_library(const fs::path& path, const std::string& key,
                                    std::string& problem) {
  Library lib;
  lib.handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
  if (lib.handle == nullptr) {
    problem = std::string("dlopen failed: ") + dlerror();
    return std::nullopt;
  }
  auto abi = reinterpret_cast<int (*)()>(dlsym(lib.handle, "sympathy_equations_abi"));
  auto tag = reinterpret_cast<const char* (*)()>(dlsym(lib.handle, "sympathy_equations_tag"));
  auto binary =
      reinterpret_cast<const char* (*)()>(dlsym(lib.handle, "sympathy_equations_binary_interface"));
  lib.create = reinterpret_cast<Library::Create>(dlsym(lib.handle, "sympathy_equations_create"));
  lib.destroy = reinterpret_cast<Library::Destroy>(dlsym(lib.handle, "sympathy_equations_destroy"));
  if (!abi || !tag || !binary || !lib.create || !lib.destroy || abi() != kEquationAbi ||
      tag() != key) {
    problem = "its library is not the one of this key (tag or ABI differ)";
    dlclose(lib.handle);
    return std::nullopt;
  }
  if (std::string(binary()) != kBinaryInterface) {
    problem = std::string("its library was compiled for another binary interface (") + binary() +
              ") than this program's (" + kBinaryInterface + ")";
    dlclose(lib.handle);
    return std::nullopt;
  }
  return lib;
}

std::mutex build_mutex;  // one build of an entry at a time in this process

}  // namespace

std::string default_equation_cache_dir() {
  if (const char* dir = std::getenv("SYMPATHY_CACHE_DIR"); dir && *dir) return dir;
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
    return (fs::path(xdg) / "sympathy").string();
  if (const char* home = std::getenv("HOME"); home && *home)
    return (fs::path(home) / ".cache" / "sympathy").string();
  throw std::runtime_error(
      "no cache directory for compiled equation systems: set SYMPATHY_CACHE_DIR (or HOME)");
}

EquationBuild build_equation_system(const EquationCase& equations, const Eigen::VectorXd& values,
                                    const std::string& cache_dir) {
  const auto start = std::chrono::steady_clock::now();
  const auto& system = equations.system();
  if (values.size() != static_cast<Eigen::Index>(system.parameters.size()))
    throw std::invalid_argument("build_equation_system: " + std::to_string(values.size()) +
                                " parameter values for " +
                                std::to_string(system.parameters.size()) + " parameters");
  const fs::path dir = cache_dir.empty() ? default_equation_cache_dir() : cache_dir;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (!fs::is_directory(dir))
    throw std::runtime_error("cannot create the equation cache directory " + dir.string() +
                             (ec ? ": " + ec.message() : ""));

  // A plug-in's source as its author wrote it (it is code, and compiled as such); a file of
  // equations' generated from its trees.
  std::string source;
  if (!equations.plugin().empty()) {
    const auto text = read_file(equations.plugin());
    if (!text) throw std::runtime_error("cannot read the plug-in " + equations.plugin());
    source =
        "// sympathy plug-in " + fs::path(equations.plugin()).filename().string() + "\n" + *text;
  } else {
    source = generate_equation_source(system);
  }
  EquationBuild build;
  build.plugin = equations.plugin();
  build.key = cache_key(source);
  build.library = (dir / (build.key + ".so")).string();

  std::optional<Library> lib;
  {
    std::lock_guard lock(build_mutex);
    std::string problem = entry_problem(dir, build.key);
    if (problem.empty()) lib = open_library(build.library, build.key, problem);
    if (!lib) {
      if (problem != "absent") build.rebuilt_because = problem;
      build.include_dir = engine_include_dir();
      compile(dir, build.key, source, build.include_dir,
              build.plugin.empty() ? "compiling an equation case file's system"
                                   : "compiling the plug-in " + build.plugin);
      build.compiled = true;
      problem = entry_problem(dir, build.key);
      if (problem.empty()) lib = open_library(build.library, build.key, problem);
      if (!lib)
        throw std::runtime_error("the equation system just compiled cannot be loaded from " +
                                 build.library + ": " + problem);
    }
  }

  std::vector<std::string> states = equations.state_names();
  std::vector<std::string> parameters = equations.parameter_names();
  std::vector<const char*> state_ptrs, parameter_ptrs;
  for (const auto& s : states) state_ptrs.push_back(s.c_str());
  for (const auto& p : parameters) parameter_ptrs.push_back(p.c_str());
  void* raw = lib->create(state_ptrs.data(), static_cast<int>(states.size()), parameter_ptrs.data(),
                          values.data(), static_cast<int>(parameters.size()));
  if (raw == nullptr) {
    dlclose(lib->handle);
    throw std::runtime_error("the equation system library " + build.library +
                             " refused to create the system (sizes differ)");
  }
  // The system owns a reference to its library: closed after the last copy is gone.
  std::shared_ptr<void> handle(lib->handle, [](void* h) { dlclose(h); });
  auto destroy = lib->destroy;
  build.system = std::shared_ptr<const OdeSystem>(
      static_cast<OdeSystem*>(raw),
      [handle, destroy](const OdeSystem* s) { destroy(const_cast<OdeSystem*>(s)); });
  build.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return build;
}

}  // namespace sympathy
