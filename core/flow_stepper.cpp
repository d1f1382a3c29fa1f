// What the flow's integrators share: the augmented right-hand side and error plumbing.
#include "flow_stepper.hpp"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace sympathy::detail {

void record_nonfinite_rhs(FlowCall& call, double t, const double* z, const double* dz, int bad) {
  const int n = call.system.dimension();
  if (call.nonfinite.empty()) {
    const auto states = call.system.state_names();
    const auto parameters = call.system.parameter_names();
    std::ostringstream s;
    s.precision(9);
    s << "the right-hand side is not finite at t = " << t << ": d" << states[bad]
      << "/dt = " << dz[bad] << " at state";
    for (int i = 0; i < n; ++i) s << (i ? ", " : " ") << states[i] << " = " << z[i];
    if (static_cast<Eigen::Index>(parameters.size()) == call.values.size() && !parameters.empty()) {
      s << " and parameters";
      for (std::size_t i = 0; i < parameters.size(); ++i)
        s << (i ? ", " : " ") << parameters[i] << " = " << call.values[static_cast<int>(i)];
    }
    call.nonfinite = s.str();
  }
}

void append_failure_details(std::ostringstream& msg, FlowCall& call) {
  if (!call.last_error.empty()) msg << " (" << call.last_error << ")";
  if (!call.nonfinite.empty()) msg << "; " << call.nonfinite;
  call.last_error.clear();
  call.nonfinite.clear();
}

int augmented_rhs(FlowCall& call, double t, const double* y, double* ydot,
                  std::vector<const double*>& columns_in, std::vector<double*>& columns_out) {
  try {
    const int n = call.system.dimension();
    columns_in.resize(call.columns);
    columns_out.resize(call.columns);
    for (int j = 0; j < call.columns; ++j) {
      columns_in[j] = y + n * (j + 1);
      columns_out[j] = ydot + n * (j + 1);
    }
    // f and the columns from one evaluation where the system can (OdeSystem::rhs_and_variational).
    call.rhs_and_variational(t, y, ydot, columns_in.data(), columns_out.data());
    return check_finite_rhs(call, t, y, ydot);
  } catch (...) {
    call.callback_error = std::current_exception();
    return -1;
  }
}

namespace {

class StepperByColumns final : public FlowStepper {
 public:
  StepperByColumns(FlowCall& call, std::function<std::unique_ptr<FlowStepper>(int)> make)
      : call_(call), make_(std::move(make)) {}
  void start(double t0, const double* z0, const Eigen::MatrixXd& seeds) override {
    auto& stepper = steppers_[call_.columns];
    if (!stepper) stepper = make_(call_.columns);
    active_ = stepper.get();
    active_->start(t0, z0, seeds);
  }
  void restart(double t) override { active().restart(t); }
  void restart_from(double t, const double* z, const Eigen::MatrixXd& S) override {
    active().restart_from(t, z, S);
  }
  void set_max_step(double hmax) override { active().set_max_step(hmax); }
  std::optional<PlannedStep> planned_step() override { return active().planned_step(); }
  void set_stop_time(double t) override { active().set_stop_time(t); }
  StepOutcome step(double t_end, double& t) override { return active().step(t_end, t); }
  const double* state() const override { return active_->state(); }
  void sensitivities(Eigen::MatrixXd& S) override { active().sensitivities(S); }
  void interpolate(double t, Eigen::VectorXd& z, Eigen::MatrixXd& S) override {
    active().interpolate(t, z, S);
  }
  void interpolate_state(double t, Eigen::VectorXd& z) override {
    active().interpolate_state(t, z);
  }
  void collect(FlowStatistics& s) override {
    if (active_) active_->collect(s);
  }
  const char* name() const override { return active_ ? active_->name() : "integrator"; }

 private:
  FlowStepper& active() {
    if (!active_) throw std::logic_error("flow stepper used before its first start");
    return *active_;
  }
  FlowCall& call_;
  std::function<std::unique_ptr<FlowStepper>(int)> make_;
  std::map<int, std::unique_ptr<FlowStepper>> steppers_;
  FlowStepper* active_ = nullptr;
};

}  // namespace

std::unique_ptr<FlowStepper> make_stepper_by_columns(
    FlowCall& call, std::function<std::unique_ptr<FlowStepper>(int columns)> make) {
  return std::make_unique<StepperByColumns>(call, std::move(make));
}

int switching_roots(FlowCall& call, double t, const double* z, double* g) {
  try {
    call.system.switching_functions(t, z, call.values.data(), g);
    return 0;
  } catch (...) {
    call.callback_error = std::current_exception();
    return -1;
  }
}

void pack_augmented(double* v, const double* z0, const Eigen::MatrixXd& seeds, int n) {
  std::copy(z0, z0 + n, v);
  Eigen::Map<Eigen::MatrixXd>(v + n, n, seeds.cols()) = seeds;
}

void augmented_columns(const double* v, int n, int columns, Eigen::MatrixXd& S) {
  S = Eigen::Map<const Eigen::MatrixXd>(v + n, n, columns);
}

void record_sundials_error(int /*code*/, const char* module, const char* function, char* msg,
                           void* user) {
  static_cast<FlowCall*>(user)->last_error = std::string(module) + "/" + function + ": " + msg;
}

void rethrow_callback_error(FlowCall& call) {
  if (!call.callback_error) return;
  auto e = call.callback_error;
  call.callback_error = nullptr;
  std::rethrow_exception(e);
}

void require(bool ok, const std::string& what) {
  if (!ok) throw std::runtime_error("SUNDIALS: " + what);
}

}  // namespace sympathy::detail
