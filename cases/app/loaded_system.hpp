// A case file of either kind (a metronome case file, an equation case file), loaded for the
// requests that run the engine on its system (continue, equilibria, curve, study): the system, the
// describer of its orbits, the parameter values of its set and overrides, named starts, and the
// checks of a parameter's name and range, so that a request is written once for both kinds.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cases/app/branch_run.hpp"
#include "cases/app/case_loading.hpp"
#include "cases/app/equation_loading.hpp"
#include "cases/app/saved_start.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/parameter_fit.hpp"

namespace sympathy::app {

// The window of one parameter a request runs over (--param, --from, --to and --at).
struct ParameterWindow {
  std::string parameter;
  double from = 0.0, to = 0.0;
  std::optional<double> at;
  // (option, value) of each end given, for LoadedSystem::check_range.
  std::vector<std::pair<std::string, double>> ends() const;
};

class LoadedSystem {
 public:
  // The case file at `path` with parameter set `params` ("" for the file's default) and `sets` on
  // top, and the recorded period at `start_data` if given (read and checked before anything is
  // compiled). `what` names the computation for the check that the model is differentiable
  // ("continue", "a branch"). `saved`: the start is a saved orbit (--parent, --from-point), read
  // once the system is known. `escapement`: a metronome case's instead of its file's (a study's
  // `escapement`); InputError for an equation case file.
  LoadedSystem(const std::string& path, const std::string& params,
               const std::vector<Assignment>& sets,
               const std::optional<std::string>& start_data = std::nullopt,
               const std::string& what = "a branch",
               const std::optional<SavedStart>& saved = std::nullopt,
               std::optional<Escapement> escapement = std::nullopt);

  bool equations() const { return equations_.has_value(); }
  const std::string& path() const;
  // The files this run reads, as (what, path) for check_distinct_outputs: the case file, a
  // plug-in's source, --start-data's recording.
  std::vector<std::pair<std::string, std::string>> inputs() const;
  const std::string& params() const;
  const OdeSystem& system() const;
  const OrbitDescriber& describer() const { return *describer_; }
  // "system compiled in ..." or "system from the cache (...)"; empty for a metronome case file.
  std::string build_note() const;

  // InputError "OPTION NAME: not a parameter of FILE; expected one of: ..." unless it is one.
  void require_parameter(const std::string& option, const std::string& name) const;
  // The parameter's value in the case (with --params and --set).
  double value_of(const std::string& parameter) const;
  // Every parameter's (name, value) in the file's parameter set `set` (without --set); InputError
  // naming the set if the file has none of that name.
  std::vector<std::pair<std::string, double>> set_values(const std::string& set) const;
  // Each (option, value) of `parameter` within its domain: an equation case file's min and max,
  // the metronome model's physical domain. InputError naming the option.
  void check_range(const std::string& parameter,
                   const std::vector<std::pair<std::string, double>>& values) const;

  // --start-data's recorded period (nullopt without it).
  const std::optional<RecordedPeriod>& start_data() const { return recorded_; }
  // Its time scaled to [0, 1] over `period` (--data-period, AUTO's dat files).
  void scale_data_time(double period);
  // The saved orbit --parent and --from-point name (nullopt without them): source()'s start.
  const std::optional<SavedOrbit>& saved_orbit() const { return saved_; }
  // InputError unless the system's orbits have a known period (an equation case file that uses t
  // declares forcing_period), and for --start-data with a forced system.
  void require_orbits() const;
  // InputError for a forced system (an equation case file that uses t): `what` is for
  // autonomous systems only.
  void require_autonomous(const std::string& what) const;

  // The start named `start` ("" is the file's [states] for an equation case file; a metronome
  // case file needs a name: InputError "--start is required"), with `initial` on top; its
  // invariant subspace (a metronome start's declared symmetry). With `data`, the recorded
  // period's first row and its period guess instead (Newton at once, in the whole state); with a
  // saved orbit, its state, period and parameter values (the same).
  BranchSource source(const std::string& start, const std::vector<Assignment>& initial,
                      const std::optional<RecordedPeriod>& data = std::nullopt) const;
  InvariantSubspace subspace(const std::string& start) const;
  // The names of the file's starts.
  std::vector<std::string> start_names() const;
  // The metronome model of a metronome case file (nullptr for an equation case file).
  const MetronomeModel* metronome_model() const { return model_.get(); }
  // The model a fit adjusts (parameter_fit.hpp), at the case's values: the metronome model (the
  // pendula free) or the equation case file's system.
  FitModel fit_model() const;

 private:
  std::vector<Assignment> sets_;  // --set, for range checks of an equation case file
  std::optional<RecordedPeriod> recorded_;
  std::optional<SavedOrbit> saved_;
  std::optional<LoadedCase> metronomes_;
  std::optional<LoadedEquations> equations_;
  std::unique_ptr<MetronomeModel> model_;
  std::unique_ptr<OrbitDescriber> describer_;
};

}  // namespace sympathy::app
