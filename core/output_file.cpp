#include "sympathy/core/output_file.hpp"

#include <fcntl.h>
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
  fd_ = ::open(path.c_str(),
               O_WRONLY | O_CREAT | O_CLOEXEC | (mode == Mode::Append ? O_APPEND : O_TRUNC), 0666);
  if (fd_ < 0) fail(path, "open for writing", errno);
  const off_t end = ::lseek(fd_, 0, SEEK_END);
  whole_ = end < 0 ? 0 : end;  // a device or a pipe: no size to keep
}

StreamFile::~StreamFile() {
  if (fd_ >= 0) ::close(fd_);  // a failure here was not asked for; close() reports it
}

void StreamFile::write_line(const std::string& line) {
  if (fd_ < 0) throw OutputError(path_ + ": write after close");
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int error = n < 0 ? errno : ENOSPC;
      // Part of the line may be in the file: cut back to the last whole one (a CSV that filled
      // the disk ended inside its last row). Fails harmlessly on a device or a pipe.
      if (done > 0 && ::ftruncate(fd_, whole_) == 0) ::lseek(fd_, whole_, SEEK_SET);
      fail(path_, "write", error);
    }
    done += static_cast<std::size_t>(n);
  }
  whole_ += static_cast<off_t>(line.size());
}

void StreamFile::close() {
  if (fd_ < 0) return;
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail(path_, "close", errno);
}

void write_file_atomically(const std::string& path, const std::string& content, mode_t mode) {
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
  // per process so that two runs writing the same name do not share a temporary; created afresh
  // (a temporary a killed run of the same process id left is removed first).
  const std::string temporary = path + ".tmp" + std::to_string(::getpid());
  ::unlink(temporary.c_str());
  const int fd =
      ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, mode);
  if (fd < 0) fail(path, "open a temporary file beside it for writing", errno);
  std::size_t done = 0;
  int error = 0;
  while (done < content.size() && error == 0) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0)
      error = n < 0 ? errno : ENOSPC;
    else
      done += static_cast<std::size_t>(n);
  }
  if (error == 0 && ::fsync(fd) != 0) error = errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    ::unlink(temporary.c_str());
    fail(path, "write", error);
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
