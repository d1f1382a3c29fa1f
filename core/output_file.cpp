#include "sympathy/core/output_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "sympathy/core/errors.hpp"

namespace sympathy {

namespace {

[[noreturn]] void fail(const std::string& path, const char* what, int error) {
  throw OutputError(path + ": cannot " + what + " (" + std::strerror(error) + ")");
}

}  // namespace

StreamFile::StreamFile(const std::string& path, Mode mode) : path_(path) {
  file_ = std::fopen(path.c_str(), mode == Mode::Append ? "a" : "w");
  if (!file_) fail(path, "open for writing", errno);
}

StreamFile::~StreamFile() {
  if (file_) std::fclose(file_);  // a failure here was not asked for; close() reports it
}

void StreamFile::write_line(const std::string& line) {
  if (!file_) throw OutputError(path_ + ": write after close");
  errno = 0;
  const std::size_t written = std::fwrite(line.data(), 1, line.size(), file_);
  if (written != line.size() || std::fflush(file_) != 0) fail(path_, "write", errno ? errno : EIO);
}

void StreamFile::close() {
  if (!file_) return;
  std::FILE* f = file_;
  file_ = nullptr;
  errno = 0;
  if (std::fflush(f) != 0) {
    const int error = errno ? errno : EIO;
    std::fclose(f);
    fail(path_, "write", error);
  }
  if (std::fclose(f) != 0) fail(path_, "close", errno ? errno : EIO);
}

void write_file_atomically(const std::string& path, const std::string& content) {
  // A device or a pipe (/dev/null, /dev/full, a FIFO) cannot be replaced by a rename, and must
  // not be: it is written in place, every write checked.
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!ec && std::filesystem::exists(status) && !std::filesystem::is_regular_file(status)) {
    StreamFile file(path);
    file.write_line(content);
    file.close();
    return;
  }
  // Beside the target (same directory, hence same file system, so that rename is atomic), named
  // per process so that two runs writing the same name do not share a temporary.
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  std::FILE* f = std::fopen(temporary.c_str(), "w");
  if (!f) fail(path, "open a temporary file beside it for writing", errno);
  errno = 0;
  const bool written = std::fwrite(content.data(), 1, content.size(), f) == content.size() &&
                       std::fflush(f) == 0 && ::fsync(::fileno(f)) == 0;
  const int error = errno ? errno : EIO;
  const bool closed = std::fclose(f) == 0;
  if (!written || !closed) {
    std::remove(temporary.c_str());
    fail(path, "write", written ? (errno ? errno : EIO) : error);
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    const int e = errno;
    std::remove(temporary.c_str());
    fail(path, "replace the file with its new version", e);
  }
}

void check_writable(const std::string& path, const std::string& option) {
  namespace fs = std::filesystem;
  const fs::path p(path);
  std::error_code ec;
  if (path.empty()) throw OutputError(option + ": expected a file name");
  if (fs::is_directory(p, ec))
    throw OutputError(option + " " + path + ": is a directory; expected a file name");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec))
    throw OutputError(option + " " + path + ": the directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw OutputError(option + " " + path + ": cannot write in " + dir.string() + " (" +
                      std::strerror(errno) + ")");
}

}  // namespace sympathy
