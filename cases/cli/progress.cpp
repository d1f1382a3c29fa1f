#include "cases/cli/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>

#include "cases/cli/common.hpp"

namespace sympathy::cli {

namespace {

bool terminal() {
  const char* term = std::getenv("TERM");
  return isatty(STDERR_FILENO) && !(term && std::strcmp(term, "dumb") == 0);
}

std::string number(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.6g", x);
  return buffer;
}

}  // namespace

std::string duration_text(double seconds) {
  const long s = std::lround(std::max(seconds, 0.0));
  if (s < 100) return std::to_string(s) + " s";
  if (s < 6000) return std::to_string((s + 30) / 60) + " min";
  const long minutes = (s + 30) / 60;
  return std::to_string(minutes / 60) + " h " + std::to_string(minutes % 60) + " min";
}

ProgressLine::ProgressLine(bool quiet) : enabled_(!quiet && terminal()) {}

double ProgressLine::seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

ProgressLine::~ProgressLine() {
  if (log_) std::fclose(log_);
  clear();
}

void ProgressLine::count(const std::string& what, std::size_t done, std::size_t total,
                         const std::string& unit, std::size_t already, const std::string& note) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  jobs_what_ = what;
  jobs_unit_ = unit;
  count_locked(done, total, already, note);
}

void ProgressLine::count_locked(std::size_t done, std::size_t total, std::size_t already,
                                const std::string& note) {
  const double elapsed = seconds();
  std::string text = jobs_what_ + ": " + std::to_string(done) + " of " + std::to_string(total) +
                     " " + jobs_unit_ + ", " + duration_text(elapsed);
  const std::size_t here = done > already ? done - already : 0;
  if (here > 0 && done < total)
    text += ", about " + duration_text(elapsed / here * (total - done)) + " left";
  if (!note.empty()) text += "; " + note;
  text_ = std::move(text);
  draw_locked(done == total);
}

void ProgressLine::start_jobs(const std::string& what, std::size_t total, const std::string& unit) {
  std::lock_guard<std::mutex> lock(mutex_);
  jobs_what_ = what;
  jobs_unit_ = unit;
  doing_.assign(total, "");
  finished_ = 0;
}

void ProgressLine::job(std::size_t i, std::string doing) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (i >= doing_.size()) return;
  doing_[i] = std::move(doing);
  std::string now;
  for (const auto& d : doing_)
    if (!d.empty()) now += (now.empty() ? "" : "; ") + d;
  count_locked(finished_, doing_.size(), 0, now);
}

void ProgressLine::finish(std::size_t i) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    ++finished_;
  }
  job(i, "");
}

void ProgressLine::position(const std::string& what, const std::string& parameter, double value,
                            double from, double to, int points) {
  if (!enabled_) return;
  std::string text = what + ": " + parameter + " = " + number(value);
  if (to != from) {
    const double share = std::clamp((value - from) / (to - from), 0.0, 1.0);
    text += ", " + std::to_string(std::lround(100 * share)) + "% of " + number(from) + " to " +
            number(to);
  }
  text += ", " + std::to_string(points) + (points == 1 ? " point, " : " points, ") +
          duration_text(seconds());
  std::lock_guard<std::mutex> lock(mutex_);
  text_ = std::move(text);
  draw_locked(false);
}

void ProgressLine::show(const std::string& text) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  text_ = text;
  draw_locked(false);
}

void ProgressLine::clear() {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  if (drawn_) std::fputs("\r\033[K", stderr);
  drawn_ = false;
  text_.clear();
}

void ProgressLine::draw_locked(bool force) {
  const double now = seconds();
  if (!force && drawn_ && now - last_draw_ < 0.1) return;
  last_draw_ = now;
  // Cut to the terminal's width: a line that wraps could not be rewritten in place.
  const std::size_t width = static_cast<std::size_t>(help_width(STDERR_FILENO)) - 1;
  const std::string shown = text_.size() > width ? text_.substr(0, width) : text_;
  std::fprintf(stderr, "\r\033[K%s", shown.c_str());
  std::fflush(stderr);
  drawn_ = true;
}

ssize_t ProgressLine::write_log(void* self, const char* data, std::size_t size) {
  auto* p = static_cast<ProgressLine*>(self);
  std::lock_guard<std::mutex> lock(p->mutex_);
  if (p->drawn_) std::fputs("\r\033[K", stderr);
  p->drawn_ = false;
  std::fwrite(data, 1, size, stderr);
  if (size > 0 && data[size - 1] == '\n' && !p->text_.empty()) p->draw_locked(true);
  std::fflush(stderr);
  return static_cast<ssize_t>(size);
}

std::FILE* ProgressLine::log() {
  if (!enabled_) return stderr;
  if (!log_) {
    cookie_io_functions_t io{};
    io.write = &ProgressLine::write_log;
    log_ = fopencookie(this, "w", io);
    if (!log_) return stderr;
    setvbuf(log_, nullptr, _IOLBF, 0);
  }
  return log_;
}

}  // namespace sympathy::cli
