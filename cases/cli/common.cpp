#include "cases/cli/common.hpp"

#include "sympathy/core/csv.hpp"

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

LoadedCase load_case(const Arguments& args) {
  return load_case(args.positional(0), args.text("--params", ""), args.assignments("--set"));
}

Accuracy accuracy(const Arguments& args) {
  const auto text = args.value("--accuracy");
  return text ? parse_accuracy(*text, "--accuracy") : Accuracy::Default;
}

FlowOptions flow_options(const Arguments& args, FlowOptions o) {
  o.rtol = args.number("--rtol", o.rtol);
  o.atol = args.number("--atol", o.atol);
  const char* given = o.method == Method::BDF ? "bdf" : o.method == Method::Adams ? "adams" : "erk";
  const std::string method = args.text("--method", given);
  if (method == "bdf") {
    o.method = Method::BDF;
    o.nonlinear_solver = NonlinearSolver::Newton;
  } else if (method == "adams") {
    o.method = Method::Adams;
    o.nonlinear_solver = NonlinearSolver::FixedPoint;
  } else if (method == "erk") {
    o.method = Method::ERK;
    o.sensitivities = Sensitivities::Augmented;  // an explicit method has no sensitivity module
  } else {
    throw InputError("--method " + method + ": expected bdf, adams or erk");
  }
  if (auto sensitivities = args.value("--sensitivities")) {
    if (*sensitivities == "forward")
      o.sensitivities = Sensitivities::ForwardModule;
    else if (*sensitivities == "augmented")
      o.sensitivities = Sensitivities::Augmented;
    else
      throw InputError("--sensitivities " + *sensitivities + ": expected forward or augmented");
  }
  check_options(o.validate(), "");
  if (!args.has("--linear-solver")) return o;  // as given (by default the flow's own choice)
  const std::string solver = args.text("--linear-solver", "");
  if (solver == "dense")
    o.linear_solver = LinearSolver::Dense;
  else if (solver == "klu")
    o.linear_solver = LinearSolver::KLU;
  else if (solver == "structured")
    o.linear_solver = LinearSolver::Structured;
  else
    throw InputError("--linear-solver " + solver + ": expected dense, klu or structured");
  return o;
}

std::string table_number(double v, const char* format) {
  if (!std::isfinite(v)) return "-";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, v);
  return buffer;
}

int segment_threads(const Arguments& args) {
  // Checked with the rest by ShootingOptions::validate (check_options names it --threads).
  if (args.has("--threads")) return args.integer("--threads", 1);
  return std::clamp(static_cast<int>(std::thread::hardware_concurrency()), 1, 256);
}

void shooting_flow_options(const Arguments& args, OrbitOptions& o) {
  o.shooting.flow = flow_options(args, o.shooting.flow);
  o.transient_flow.linear_solver = o.shooting.flow.linear_solver;
  if (args.has("--method")) o.switch_when_stiff = false;  // the method asked for, stiff or not
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
