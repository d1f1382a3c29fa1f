// Checked output (core/output_file.hpp): every failure to write is an OutputError naming the path
// and the operating system's reason, and a whole file is replaced atomically or not at all.
#include "sympathy/core/output_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "tests/support/errors.hpp"

namespace sympathy {
namespace {

namespace fs = std::filesystem;
using testing::expect_mentions;

// A fresh, empty directory for one test (named after it and the process), removed afterwards.
class ScratchDirectory {
 public:
  ScratchDirectory() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() /
            ("sympathy_output_file_test_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDirectory() {
    std::error_code ec;
    fs::permissions(path_, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path_, ec);
  }
  ScratchDirectory(const ScratchDirectory&) = delete;
  ScratchDirectory& operator=(const ScratchDirectory&) = delete;

  const fs::path& path() const { return path_; }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  // The names of the directory's entries, sorted.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(path_))
      names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

 private:
  fs::path path_;
};

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// The message of the OutputError that `f` throws; fails the test if it throws none.
template <class F>
std::string output_error_of(F&& f) {
  try {
    f();
  } catch (const OutputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no OutputError thrown";
  return "";
}

// /dev/full accepts the open and fails every write with ENOSPC (Linux, full(4)); a line is flushed
// as it is written, so the first write_line already fails, with the path and strerror(ENOSPC).
TEST(StreamFile, FullDeviceNamesPathAndReason) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  StreamFile file("/dev/full");
  const std::string message = output_error_of([&] { file.write_line("index,value\n"); });
  expect_mentions(message, {"/dev/full", "No space left on device"});
}

// Each line reaches the file when write_line returns (a run that stops keeps it); close() is
// idempotent and a write after it is an OutputError. Exact text.
TEST(StreamFile, EachLineReachesTheFileAtOnce) {
  const ScratchDirectory dir;
  const std::string path = dir.file("rows.csv");
  StreamFile file(path);
  file.write_line("a,b\n");
  EXPECT_EQ(read_all(path), "a,b\n");
  file.write_line("1,2\n");
  EXPECT_EQ(read_all(path), "a,b\n1,2\n");
  file.close();
  EXPECT_NO_THROW(file.close());
  expect_mentions(output_error_of([&] { file.write_line("3,4\n"); }), {path, "after close"});
  EXPECT_EQ(read_all(path), "a,b\n1,2\n");
}

// A file that cannot be opened (its directory is missing) is an OutputError from the constructor,
// with the path and strerror(ENOENT).
TEST(StreamFile, MissingDirectoryNamesPathAndReason) {
  const ScratchDirectory dir;
  const std::string path = dir.file("missing/rows.csv");
  expect_mentions(output_error_of([&] { StreamFile file(path); }),
                  {path, "No such file or directory"});
}

// A CSV on /dev/full: the header (written in the constructor) or the first row must throw an
// OutputError; either is accepted, but something must throw before the writer is destroyed.
TEST(CsvOutput, FullDeviceThrows) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full on this system";
  const std::string message = output_error_of([] {
    CsvWriter csv("/dev/full", {"index", "value"});
    csv.row(std::vector<double>{1.0, 0.5});
    csv.close();
  });
  expect_mentions(message, {"/dev/full", "No space left on device"});
}

// The content read back is the content written, byte for byte (a NUL and no final newline
// included), and nothing but the file is left in the directory.
TEST(AtomicWrite, WritesContentExactly) {
  const ScratchDirectory dir;
  const std::string path = dir.file("report.json");
  const std::string content = std::string("{\"a\": 1,\n \"b\": [0.1, 2]}\n") + '\0' + "tail";
  write_file_atomically(path, content);
  EXPECT_EQ(read_all(path), content);
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"report.json"});
}

// Replacing an existing file leaves the new content (shorter than the old: no old bytes remain)
// and no temporary beside it.
TEST(AtomicWrite, ReplacesAndLeavesNoTemporary) {
  const ScratchDirectory dir;
  const std::string path = dir.file("report.json");
  write_file_atomically(path, "the earlier, longer version of the report\n");
  write_file_atomically(path, "new\n");
  EXPECT_EQ(read_all(path), "new\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"report.json"});
}

// A path in a missing directory: OutputError naming the path and strerror(ENOENT), and nothing is
// created (neither the directory nor a file in the parent).
TEST(AtomicWrite, MissingDirectoryThrowsAndLeavesNothing) {
  const ScratchDirectory dir;
  const std::string path = dir.file("missing/report.json");
  expect_mentions(output_error_of([&] { write_file_atomically(path, "{}\n"); }),
                  {path, "No such file or directory"});
  EXPECT_FALSE(fs::exists(dir.path() / "missing"));
  EXPECT_TRUE(dir.entries().empty());
}

// The file-size limit (RLIMIT_FSIZE) at `bytes` while it lives, SIGXFSZ ignored so that writes
// past it fail with EFBIG; both restored after.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    ok_ = ::getrlimit(RLIMIT_FSIZE, &saved_) == 0;
    rlimit limited = saved_;
    limited.rlim_cur = bytes;
    previous_ = std::signal(SIGXFSZ, SIG_IGN);
    ok_ = ok_ && ::setrlimit(RLIMIT_FSIZE, &limited) == 0;
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;
  bool ok() const { return ok_; }

 private:
  rlimit saved_{};
  void (*previous_)(int) = SIG_DFL;
  bool ok_ = false;
};

// The write itself fails (the file-size limit, RLIMIT_FSIZE, applies to root as well: writes past
// it fail with EFBIG once SIGXFSZ is ignored): OutputError naming the path and strerror(EFBIG),
// the earlier file keeps its content and its temporary is removed. Nothing is printed while the
// limit is in force.
TEST(AtomicWrite, FailedWriteKeepsEarlierFile) {
  const ScratchDirectory dir;
  const std::string path = dir.file("report.json");
  write_file_atomically(path, "earlier\n");
  const std::string content(1 << 16, 'x');  // past any stdio buffer, so the write reaches the OS

  std::string message;
  bool thrown = false;
  {
    const FileSizeLimit limit(16);
    ASSERT_TRUE(limit.ok());
    try {
      write_file_atomically(path, content);
    } catch (const OutputError& e) {
      thrown = true;
      message = e.what();
    }
  }

  ASSERT_TRUE(thrown) << "no OutputError when the write failed";
  expect_mentions(message, {path, "File too large"});
  EXPECT_EQ(read_all(path), "earlier\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"report.json"});
}

// A disk that fills inside a line (here the file-size limit, as above, at 100 bytes with lines of
// 30): the write fails with the path and the reason, and the file keeps the three whole lines
// only (issue 32: a CSV that filled the disk ended inside its last row).
TEST(StreamFile, FailedWriteLeavesWholeLines) {
  const ScratchDirectory dir;
  const std::string path = dir.file("rows.csv");
  const std::string line = std::string(29, 'r') + "\n";
  std::string message;
  int written = 0;
  {
    const FileSizeLimit limit(100);
    ASSERT_TRUE(limit.ok());
    StreamFile file(path);
    try {
      for (; written < 10; ++written) file.write_line(line);
    } catch (const OutputError& e) {
      message = e.what();
    }
  }
  EXPECT_EQ(written, 3);
  expect_mentions(message, {path, "File too large"});
  EXPECT_EQ(read_all(path), line + line + line);
}

// The temporary cannot be created (a directory without write permission, chmod 0555): OutputError
// naming the path and strerror(EACCES), and the earlier file keeps its content. Root is not
// stopped by permissions, so there the case cannot be made this way (FailedWriteKeepsEarlierFile
// covers a failed replacement for root too).
TEST(AtomicWrite, UnwritableDirectoryKeepsEarlierFile) {
  if (::geteuid() == 0)
    GTEST_SKIP() << "running as root: directory permissions do not stop root from writing";
  const ScratchDirectory dir;
  const std::string path = dir.file("report.json");
  write_file_atomically(path, "earlier\n");
  ASSERT_EQ(::chmod(dir.path().c_str(), 0555), 0);
  const std::string message = output_error_of([&] { write_file_atomically(path, "new\n"); });
  ::chmod(dir.path().c_str(), 0755);
  expect_mentions(message, {path, "Permission denied"});
  EXPECT_EQ(read_all(path), "earlier\n");
  EXPECT_EQ(dir.entries(), std::vector<std::string>{"report.json"});
}

// A device is written in place (not replaced by a rename): /dev/null takes the content and stays
// a character device.
TEST(AtomicWrite, DeviceIsWrittenInPlace) {
  if (!fs::exists("/dev/null")) GTEST_SKIP() << "no /dev/null on this system";
  EXPECT_NO_THROW(write_file_atomically("/dev/null", "{}\n"));
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
}

// check_writable names the option, the path and what is wrong; an ordinary path in a writable
// directory passes, and nothing is created by the check.
TEST(CheckWritable, MissingDirectory) {
  const ScratchDirectory dir;
  const std::string path = dir.file("missing/branch.csv");
  expect_mentions(output_error_of([&] { check_writable(path, "--csv"); }),
                  {"--csv", path, "does not exist"});
}

TEST(CheckWritable, DirectoryGivenAsFile) {
  const ScratchDirectory dir;
  const std::string path = dir.path().string();
  expect_mentions(output_error_of([&] { check_writable(path, "--json"); }),
                  {"--json", path, "is a directory"});
}

TEST(CheckWritable, EmptyPath) {
  expect_mentions(output_error_of([] { check_writable("", "--json"); }),
                  {"--json", "expected a file name"});
}

TEST(CheckWritable, OrdinaryWritablePath) {
  const ScratchDirectory dir;
  const std::string path = dir.file("branch.csv");
  EXPECT_NO_THROW(check_writable(path, "--csv"));
  EXPECT_FALSE(fs::exists(path));
  // An existing file may be overwritten.
  write_file_atomically(path, "old\n");
  EXPECT_NO_THROW(check_writable(path, "--csv"));
}

// A directory without write permission (chmod 0555): "cannot write in" it, with strerror(EACCES).
// Skipped as root, whom permissions do not stop.
TEST(CheckWritable, UnwritableDirectory) {
  if (::geteuid() == 0)
    GTEST_SKIP() << "running as root: directory permissions do not stop root from writing";
  const ScratchDirectory dir;
  const std::string path = dir.file("branch.csv");
  ASSERT_EQ(::chmod(dir.path().c_str(), 0555), 0);
  const std::string message = output_error_of([&] { check_writable(path, "--csv"); });
  ::chmod(dir.path().c_str(), 0755);
  expect_mentions(message, {"--csv", path, "cannot write in", "Permission denied"});
}

}  // namespace
}  // namespace sympathy
