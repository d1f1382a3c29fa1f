// Reading recordings: every kind of bad data is rejected with the file, the line, the column and
// what was expected.
#include "sympathy/core/recording.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/errors.hpp"
#include "tests/support/errors.hpp"

namespace sympathy {
namespace {

using testing::expect_mentions;

const std::vector<std::string> kStates{"x", "th1", "vx", "vth1"};

class RecordingErrors : public ::testing::Test {
 protected:
  std::string write(const std::string& text) {
    return path_ = testing::write_test_file("sympathy_recording_tests", ".csv", text);
  }
  // The message of the InputError reading `text` gives; fails the test if there is none.
  std::string error_of(const std::string& text) {
    const std::string path = write(text);
    return testing::input_error_of([&] { read_recording(path, kStates, "the case"); });
  }
  std::string path_;
};

TEST_F(RecordingErrors, ValidRecordingReads) {
  // Any subset of states in any order, CRLF line ends, spaces, blank lines at the end.
  const auto path =
      write("t, vth1 ,th1\r\n0,0,0.3\r\n0.01,-0.37,0.298\r\n0.025,-0.7,0.295\r\n\n\n");
  const Recording r = read_recording(path, kStates);
  EXPECT_EQ(r.columns, (std::vector<std::string>{"vth1", "th1"}));
  EXPECT_EQ(r.components, (std::vector<int>{3, 1}));
  ASSERT_EQ(r.samples(), 3);
  EXPECT_EQ(r.times[2], 0.025);
  EXPECT_EQ(r.values(1, 0), -0.37);
  EXPECT_EQ(r.values(2, 1), 0.295);
  EXPECT_EQ(r.lines, (std::vector<int>{2, 3, 4}));
}

// A directory is named as one (issue 32: read as an empty file, "the file is empty").
TEST_F(RecordingErrors, DirectoryIsNamedAsSuch) {
  const auto dir = std::filesystem::temp_directory_path() / "sympathy_recording_dir";
  std::filesystem::create_directories(dir);
  const std::string message =
      testing::input_error_of([&] { read_recording(dir.string(), kStates); });
  EXPECT_EQ(message, dir.string() + ": cannot read the file (a directory; expected a CSV file)");
}

TEST_F(RecordingErrors, MissingFile) {
  try {
    read_recording("/nonexistent/rec.csv", kStates);
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError& e) {
    expect_mentions(e.what(), {"/nonexistent/rec.csv", "cannot read"});
  }
}

TEST_F(RecordingErrors, EmptyFile) {
  expect_mentions(error_of(""), {path_, "empty", "expected a header line"});
}

TEST_F(RecordingErrors, NoRows) {
  expect_mentions(error_of("t,th1\n"), {path_, "no rows after the header"});
}

TEST_F(RecordingErrors, TimeColumnMissing) {
  expect_mentions(error_of("time,th1\n0,0.3\n"),
                  {path_ + ":1", "column 1 is 'time'", "expected 't'"});
}

TEST_F(RecordingErrors, UnknownColumn) {
  expect_mentions(error_of("t,th1,th2\n0,0.3,0.1\n"),
                  {path_ + ":1", "column 3 'th2'", "not a state of the case",
                   "expected t, then any of: x, th1, vx, vth1"});
}

TEST_F(RecordingErrors, NoStateColumn) {
  expect_mentions(error_of("t\n0\n1\n"), {path_ + ":1", "only a time column", "one or more of"});
}

TEST_F(RecordingErrors, RepeatedColumn) {
  expect_mentions(error_of("t,th1,th1\n0,0.3,0.3\n"),
                  {path_ + ":1", "column 3", "'th1' repeats column 2", "distinct"});
}

TEST_F(RecordingErrors, UnnamedColumn) {
  expect_mentions(error_of("t,,th1\n0,1,0.3\n"), {path_ + ":1", "column 2 has no name"});
}

TEST_F(RecordingErrors, MissingField) {
  expect_mentions(error_of("t,x,th1\n0,0,0.3\n0.01,0.298\n"),
                  {path_ + ":3", "expected 3 fields (t, x, th1), got 2"});
}

TEST_F(RecordingErrors, EmptyRow) {
  expect_mentions(error_of("t,th1\n0,0.3\n\n0.02,0.29\n"),
                  {path_ + ":3", "empty row", "expected 2 fields (t, th1)"});
}

TEST_F(RecordingErrors, EmptyField) {
  expect_mentions(error_of("t,x,th1\n0,0,0.3\n0.01,,0.29\n"),
                  {path_ + ":3", "column 'x' (field 2)", "empty field", "expected a number"});
}

TEST_F(RecordingErrors, NaN) {
  expect_mentions(error_of("t,th1\n0,0.3\n0.01,nan\n"),
                  {path_ + ":3", "column 'th1' (field 2)", "expected a finite number, got 'nan'"});
  expect_mentions(error_of("t,th1\n0,0.3\n0.01,-inf\n"),
                  {path_ + ":3", "column 'th1'", "expected a finite number, got '-inf'"});
}

TEST_F(RecordingErrors, NotANumber) {
  expect_mentions(error_of("t,th1\n0,0.3\n0.01,0.29rad\n"),
                  {path_ + ":3", "column 'th1' (field 2)", "expected a number, got '0.29rad'"});
}

TEST_F(RecordingErrors, NonIncreasingTime) {
  expect_mentions(error_of("t,th1\n0,0.3\n0.01,0.29\n0.01,0.28\n"),
                  {path_ + ":4", "column 't'", "time 0.01 after 0.01 (line 3)",
                   "expected strictly increasing times"});
  expect_mentions(error_of("t,th1\n0,0.3\n0.02,0.29\n0.01,0.28\n"),
                  {path_ + ":4", "time 0.01 after 0.02"});
}

// A value whose square overflows (issue 32: one sample of 1e300 made a fit report "RSS 0 -> 0",
// "RMS -nan" and "converged") is refused with its line and column; 1e150 itself is accepted.
TEST_F(RecordingErrors, ValueWhoseSquareOverflowsIsRefused) {
  const std::string error = error_of("t,x\n0,0.1\n0.01,1e300\n");
  EXPECT_EQ(error, path_ +
                       ":3: column 'x': 1e+300; expected a value of magnitude at most 1e150 (its "
                       "square must not overflow in a least-squares fit)");
  EXPECT_NE(error_of("t,th1\n0,-2e150\n").find(":2: column 'th1': -2e+150"), std::string::npos);
  EXPECT_NO_THROW(read_recording(write("t,x\n0,1e150\n0.01,-1e150\n"), kStates));
}

}  // namespace
}  // namespace sympathy
