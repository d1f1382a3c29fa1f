#include "sympathy/cases/equation_compiler.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "sympathy/cases/equation_codegen.hpp"
#include "sympathy/cases/equation_toolchain.hpp"
#include "sympathy/cases/sha256.hpp"
#include "sympathy/core/binary_interface.hpp"
#include "sympathy/core/errors.hpp"
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

// The cache is a security boundary: a library found there runs in this process. It is trusted
// only as far as its owner and its directories: an entry is loaded only if the cache directory,
// every directory above it (unless root owns it and it is sticky, as /tmp) and the entry's files
// belong to this user or root and are writable by nobody else; and the checks are made on the
// descriptor that is then loaded, so nothing can be swapped between check and dlopen.
bool trusted_owner(uid_t uid) {
  return uid == ::geteuid() || uid == 0;
}

std::string mode_text(mode_t mode) {
  char text[8];
  std::snprintf(text, sizeof text, "%04o", static_cast<unsigned>(mode & 07777));
  return text;
}

// Why the cache directory `dir` cannot be trusted, or "".
std::string directory_problem(const fs::path& dir) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(dir, ec);
  if (ec) return "cannot resolve it: " + ec.message();
  for (fs::path p = canonical;; p = p.parent_path()) {
    struct stat st {};
    if (::lstat(p.c_str(), &st) != 0) return "cannot examine " + p.string();
    const bool writable_by_others = (st.st_mode & (S_IWGRP | S_IWOTH)) != 0;
    const bool shared_sticky = p != canonical && st.st_uid == 0 && (st.st_mode & S_ISVTX) != 0;
    if (!trusted_owner(st.st_uid))
      return (p == canonical ? "it" : p.string()) + " belongs to another user (uid " +
             std::to_string(st.st_uid) + ")";
    if (writable_by_others && !shared_sticky)
      return (p == canonical ? "it" : p.string()) + " is writable by group or others (mode " +
             mode_text(st.st_mode) + ")";
    if (p == p.parent_path()) break;
  }
  return "";
}

// A file of an entry opened for checking and loading: never through a symbolic link, a regular
// file of this user's or root's that nobody else can write; its bytes read from the descriptor.
struct OpenedFile {
  int fd = -1;
  dev_t device = 0;
  ino_t inode = 0;
  std::string bytes;
  OpenedFile() = default;
  OpenedFile(const OpenedFile&) = delete;
  OpenedFile& operator=(const OpenedFile&) = delete;
  ~OpenedFile() {
    if (fd >= 0) ::close(fd);
  }
  int release() { return std::exchange(fd, -1); }
};

// Opens `path` into `file`; returns "" or why it is not to be trusted ("absent" if it is not
// there).
std::string open_protected(const fs::path& path, const std::string& what, OpenedFile& file) {
  file.fd = ::open(path.c_str(), O_RDONLY | O_NOFOLLOW | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
  if (file.fd < 0) {
    if (errno == ENOENT) return "absent";
    if (errno == ELOOP) return "its " + what + " is a symbolic link";
    return "its " + what + " cannot be opened: " + std::strerror(errno);
  }
  struct stat st {};
  if (::fstat(file.fd, &st) != 0) return "its " + what + " cannot be examined";
  if (!S_ISREG(st.st_mode)) return "its " + what + " is not a regular file";
  if (!trusted_owner(st.st_uid))
    return "its " + what + " belongs to another user (uid " + std::to_string(st.st_uid) + ")";
  if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0)
    return "its " + what + " is writable by group or others (mode " + mode_text(st.st_mode) + ")";
  file.device = st.st_dev;
  file.inode = st.st_ino;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t n = ::read(file.fd, buffer, sizeof buffer);
    if (n == 0) break;
    if (n < 0) {
      if (errno == EINTR) continue;
      return "its " + what + " cannot be read: " + std::strerror(errno);
    }
    file.bytes.append(buffer, static_cast<std::size_t>(n));
  }
  return "";
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

// SIGINT, SIGTERM and SIGHUP while the compiler runs: recorded (their handlers set without
// SA_RESTART, so that waitpid returns), the compiler stopped, its files removed, and Interrupted
// thrown; the handlers before are restored afterwards (and not called: the exception is the
// command's news of the signal). (The first Ctrl-C during a compile exited
// 130 and left the compiler running and its temporaries in the cache.)
volatile std::sig_atomic_t compile_signal = 0;
extern "C" void on_compile_signal(int signal) {
  compile_signal = signal;
}

class CompileSignals {
 public:
  CompileSignals() {
    compile_signal = 0;
    struct sigaction action {};
    action.sa_handler = on_compile_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
      ::sigaction(kSignals[i], &action, &previous_[i]);
  }
  ~CompileSignals() {
    // The signal is not raised again (a handler that ends the process would leave the build
    // directory behind): Interrupted, thrown after the compile's files are removed, says it.
    for (std::size_t i = 0; i < std::size(kSignals); ++i)
      ::sigaction(kSignals[i], &previous_[i], nullptr);
  }
  CompileSignals(const CompileSignals&) = delete;
  CompileSignals& operator=(const CompileSignals&) = delete;

 private:
  static constexpr int kSignals[] = {SIGINT, SIGTERM, SIGHUP};
  struct sigaction previous_[3]{};
};

constexpr int kInterruptedStatus = -2;

// Runs `argv` (no shell), its output into `log`; returns its exit status (-1 if it could not
// start, kInterruptedStatus if a signal stopped it: the child is terminated and reaped).
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
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
    if (compile_signal != 0) {
      ::kill(pid, SIGTERM);
      while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
      }
      return kInterruptedStatus;
    }
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// Compiles `source` into the cache entry `key` (KEY.cpp, KEY.so, KEY.manifest) against the
// engine headers in `include`; `built` is the new library, opened and checked as an entry's is,
// to be loaded through that descriptor (not read and hashed again from the cache).
void compile(const fs::path& dir, const std::string& key, const std::string& source,
             const std::string& include, const std::string& what, OpenedFile& built) {
  write_file_atomically((dir / (key + ".cpp")).string(), source, 0644);
  // The compiler's output in a directory of its own with mode 0700 (mkdtemp), made 0644 there
  // before it is moved into place: no other account can open the library for writing between its
  // creation and its manifest.
  std::string private_dir = (dir / (key + ".build.XXXXXX")).string();
  if (::mkdtemp(private_dir.data()) == nullptr)
    throw std::runtime_error("cannot make a build directory in " + dir.string() + ": " +
                             std::strerror(errno));
  struct RemoveDir {
    fs::path path;
    ~RemoveDir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  } cleanup{private_dir};
  const fs::path library = fs::path(private_dir) / (key + ".so");
  const fs::path log = fs::path(private_dir) / (key + ".log");
  std::vector<std::string> argv{toolchain::kCompiler};
  const auto flags = compile_flags();
  argv.insert(argv.end(), flags.begin(), flags.end());
  argv.insert(argv.end(), {"-DSYMPATHY_EQUATIONS_TAG=\"" + key + "\"", "-I" + include,
                           "-I" + std::string(toolchain::kEigenInclude), "-o", library.string(),
                           (dir / (key + ".cpp")).string()});
  int status = 0;
  {
    const CompileSignals signals;
    status = run(argv, log);
  }
  if (status == kInterruptedStatus)
    throw Interrupted(std::string(what) + " was stopped by a signal; nothing of it is kept");
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
  if (::chmod(library.c_str(), 0644) != 0)
    throw std::runtime_error("cannot set the mode of the compiled library " + library.string());
  if (const auto problem = open_protected(library, "library", built); !problem.empty())
    throw std::runtime_error("cannot read the compiled library " + library.string() + ": " +
                             problem);
  fs::rename(library, dir / (key + ".so"));  // atomic within the directory
  write_file_atomically((dir / (key + ".manifest")).string(),
                        manifest_text(key, sha256_hex(built.bytes)), 0644);
}

// Why the entry `key` cannot be loaded, or "" if its manifest vouches for its library, which is
// then open in `library` (the descriptor that is loaded).
std::string entry_problem(const fs::path& dir, const std::string& key, OpenedFile& library) {
  OpenedFile manifest;
  const auto manifest_problem = open_protected(dir / (key + ".manifest"), "manifest", manifest);
  const auto library_problem = open_protected(dir / (key + ".so"), "library", library);
  if (manifest_problem == "absent" && library_problem == "absent") return "absent";
  if (manifest_problem == "absent") return "its manifest is missing";
  if (library_problem == "absent") return "its library is missing";
  if (!manifest_problem.empty()) return manifest_problem;
  if (!library_problem.empty()) return library_problem;
  if (manifest.bytes != manifest_text(key, sha256_hex(library.bytes)))
    return "its library does not match its manifest (corrupt or foreign)";
  return "";
}

// The name under which dlopen loads the checked descriptor of `library`: /proc/self/fd/N. The
// descriptor stays open for the life of the process (one per library file loaded), so that no
// other library is ever opened under the same name: glibc matches a dlopen's name against the
// libraries already loaded, and dlclose need not unload a C++ library (unique symbols).
std::string loadable_name(OpenedFile& library) {
  static std::mutex mutex;
  static std::map<std::pair<dev_t, ino_t>, int> kept;
  std::lock_guard lock(mutex);
  const auto [it, inserted] = kept.emplace(std::pair{library.device, library.inode}, library.fd);
  if (inserted) library.release();  // the same file (device and inode) reuses its descriptor
  return "/proc/self/fd/" + std::to_string(it->second);
}

struct Library {
  void* handle = nullptr;
  using Create = void* (*)(const char* const*, int, const char* const*, const double*, int);
  using Destroy = void (*)(void*);
  Create create = nullptr;
  Destroy destroy = nullptr;
};

// dlopen and the C interface's checks; nullopt (closed again) when the tag or ABI differ.
std::optional<Library> open_library(OpenedFile& library, const std::string& key,
                                    std::string& problem) {
  Library lib;
  lib.handle = dlopen(loadable_name(library).c_str(), RTLD_NOW | RTLD_LOCAL);
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
  if (!fs::exists(dir, ec)) {
    fs::create_directories(dir.parent_path().empty() ? fs::path(".") : dir.parent_path(), ec);
    if (::mkdir(dir.c_str(), 0700) != 0 && errno != EEXIST)
      throw std::runtime_error("cannot create the equation cache directory " + dir.string() + ": " +
                               std::strerror(errno));
  }
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error("the equation cache directory " + dir.string() +
                             " is not a directory");
  if (const auto problem = directory_problem(dir); !problem.empty())
    throw std::runtime_error(
        "the equation cache directory " + dir.string() +
        " is not safe to load code from: " + problem +
        ". Another account could plant a library there that this program would run. Use a "
        "directory of your own, writable by you alone (the default, ~/.cache/sympathy, is made "
        "with mode 0700); to share compiled systems, use a directory that root owns and fills, "
        "read-only to everyone else");

  // A plug-in's source as its author wrote it (it is code, and compiled as such); a file of
  // equations' generated from its trees.
  std::string source;
  if (!equations.plugin().empty()) {
    // The plug-in's text alone: nothing of the case file (not even the plug-in's name, which a
    // newline could turn into source lines) reaches the compiler.
    const auto text = read_file(equations.plugin());
    if (!text) throw std::runtime_error("cannot read the plug-in " + equations.plugin());
    source = *text;
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
    std::string problem;
    {
      OpenedFile library;
      problem = entry_problem(dir, build.key, library);
      if (problem.empty()) lib = open_library(library, build.key, problem);
    }
    if (!lib) {
      if (problem != "absent") build.rebuilt_because = problem;
      build.include_dir = engine_include_dir();
      OpenedFile library;
      compile(dir, build.key, source, build.include_dir,
              build.plugin.empty() ? "compiling an equation case file's system"
                                   : "compiling the plug-in " + build.plugin,
              library);
      build.compiled = true;
      lib = open_library(library, build.key, problem);
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
    throw std::runtime_error(
        "the equation system library " + build.library +
        " refused to create the system (its sizes differ from the case file's, or its "
        "constructor threw)");
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
