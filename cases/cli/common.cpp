#include "cases/cli/common.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <utility>

namespace sympathy::cli {

std::string table_number(double v, const char* format) {
  if (!std::isfinite(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int) {
  if (g_interrupted.exchange(true)) std::_Exit(130);
}

}  // namespace

extern "C" void on_interrupt_exit(int) {
  // Async-signal-safe: write(2) and _exit alone.
  static const char message[] = "sympathy: interrupted: stopped, no file written (exit 6)\n";
  const ssize_t ignored = ::write(2, message, sizeof message - 1);
  static_cast<void>(ignored);
  ::_exit(6);
}

void exit_on_interrupt() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, on_interrupt_exit);
}

const std::atomic<bool>* interrupt_flag() {
  for (int signal : {SIGINT, SIGTERM, SIGHUP}) std::signal(signal, on_interrupt);
  return &g_interrupted;
}

}  // namespace sympathy::cli
