// What a long command shows on a terminal while it runs: one status line on stderr, rewritten in
// place at most ten times a second and erased at the end. Nothing when stderr is not a terminal
// (a log, a pipe, CI), when TERM is "dumb", or with --quiet: the command's output is then exactly
// what it would be without it.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdio>
#include <mutex>
#include <string>
#include <vector>

namespace sympathy::cli {

class ProgressLine {
 public:
  explicit ProgressLine(bool quiet);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  bool enabled() const { return enabled_; }

  // A count with the time left, from the rate so far: "map: 1 of 3 orbits, 41 s, about 1 min
  // left". `already` were done before this run (a resumed journal) and do not count for the rate.
  void count(const std::string& what, std::size_t done, std::size_t total, const std::string& unit,
             std::size_t already = 0, const std::string& note = "");
  // A continuation's place in its window: "continue: k = 48.2, 61% of 30 to 60, 57 points".
  void position(const std::string& what, const std::string& parameter, double value, double from,
                double to, int points);
  // Jobs run side by side (a map's orbits, a study's branches): start_jobs names them and their
  // count; job(i, what) says what job i is doing, finish(i) that it is done; the line shows the
  // count done with the time left and what each running job is doing. Thread-safe.
  void start_jobs(const std::string& what, std::size_t total, const std::string& unit);
  void job(std::size_t i, std::string doing);
  void finish(std::size_t i);
  // Any text.
  void show(const std::string& text);
  void clear();

  // Where the log lines printed meanwhile go: on a terminal, a stream that erases the status
  // line before each line and draws it again after; else stderr itself.
  std::FILE* log();

 private:
  static ssize_t write_log(void* self, const char* data, std::size_t size);
  void draw_locked(bool force);
  void count_locked(std::size_t done, std::size_t total, std::size_t already,
                    const std::string& note);

  bool enabled_ = false;
  std::mutex mutex_;
  std::string text_;
  bool drawn_ = false;
  double last_draw_ = -1.0;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  double seconds() const;  // since the line was made
  std::FILE* log_ = nullptr;
  // The jobs (start_jobs).
  std::string jobs_what_, jobs_unit_;
  std::vector<std::string> doing_;
  std::size_t finished_ = 0;
};

// Seconds as "41 s", "3 min", "2 h 5 min".
std::string duration_text(double seconds);

}  // namespace sympathy::cli
