// Checked output: the one way sympathy writes files, so that nothing computed is lost silently.
//
// Two kinds of file. A stream (CSV rows, one branch point at a time) is written a whole line at
// a time and flushed after each, so that a run that stops keeps every line before it; every
// write, flush and close is checked. A whole file (a JSON report, a fitted case) is written to a
// temporary beside its target and renamed over it only when complete, so a failure or a signal
// leaves the earlier file of that name as it was, never a truncated one. Either failure is an
// OutputError naming the path and the operating system's reason (e.g. "No space left on device"
// from /dev/full). A stream may also be opened to append (a journal that a resumed run extends:
// continuation/task_journal).
#pragma once

#include <sys/types.h>
#include <cstdio>

#include <string>

namespace sympathy {

class StreamFile {
 public:
  enum class Mode { Truncate, Append };
  // Opens `path`, truncated (or, with Mode::Append, created if absent and written at its end);
  // throws OutputError if it cannot.
  explicit StreamFile(const std::string& path, Mode mode = Mode::Truncate);
  ~StreamFile();
  StreamFile(const StreamFile&) = delete;
  StreamFile& operator=(const StreamFile&) = delete;

  // Writes `line` (which should end in '\n') whole, straight to the file (no buffer); throws
  // OutputError. A write that fails part way (a full disk) is cut back to the last whole line, so
  // the file ends with whole rows (where the file can be truncated: not a device or a pipe).
  void write_line(const std::string& line);
  // Closes the file, checking that everything reached it; throws OutputError. Idempotent.
  void close();
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  off_t whole_ = 0;  // the file's size after the last whole line
};

// Writes `content` to `path` atomically (a temporary beside it, then rename); throws OutputError.
// A path that names a device or a pipe (/dev/null, /dev/full) is written in place instead. The
// temporary is created afresh (never through a link) with `mode` (less the umask) from the start,
// so no other account can open it for writing at any moment where `mode` does not allow it.
void write_file_atomically(const std::string& path, const std::string& content, mode_t mode = 0666);

// Checks, before any work, that `path` can be written: its directory exists and is writable, and
// it is not a directory. Throws OutputError naming `option` (e.g. "--json") and the path.
void check_writable(const std::string& path, const std::string& option);

}  // namespace sympathy
