// Error types shared by every layer.
#pragma once

#include <stdexcept>
#include <string>

namespace sympathy {

// Bad input (a case file, a command-line argument, a data file), found before any computation.
// The message names the source (file and line, or argument), the key and what was expected.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// An output that could not be written (a full disk, a missing directory, no permission). The
// message names the path and the operating system's reason.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Work stopped by SIGINT, SIGTERM or SIGHUP where it cannot be resumed part way (an equation
// system's compile): what it started is stopped and removed; the command exits 6.
class Interrupted : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Raised when the integrator fails (step size underflow, too many steps, a failing right-hand
// side); `time` is where it stopped.
class IntegrationError : public std::runtime_error {
 public:
  IntegrationError(const std::string& what, double t) : std::runtime_error(what), t_(t) {}
  double time() const { return t_; }

 private:
  double t_;
};

}  // namespace sympathy
