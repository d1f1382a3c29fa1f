// The Python module `sympathy`: a case file (of either kind, or a dict: case_dict.hpp) as a Case,
// and its simulate, orbit, continue_branch, curve, equilibria and fit, and study: each the command
// of the same name run on the same code as the program (the application layer, cases/app/): keyword
// arguments are the command's options (python_options.hpp), results the engine's as NumPy arrays
// and objects (python_results.hpp). Nothing numerical happens here.
//
// The engine runs with the GIL released. Its stop check (polled between a branch's points, and
// between a simulation's output samples) takes the GIL back for a moment to run Python's pending
// signal handlers (PyErr_CheckSignals): Ctrl-C then ends the run after the current point and the
// call returns what was computed, its stop "interrupted", as the program does on SIGINT.
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "case_dict.hpp"
#include "cases/app/basins_run.hpp"
#include "cases/app/case_arguments.hpp"
#include "cases/app/equilibrium_curve_run.hpp"
#include "cases/app/fit_run.hpp"
#include "cases/app/map_run.hpp"
#include "cases/app/orbit_run.hpp"
#include "cases/app/requests.hpp"
#include "cases/app/simulation_run.hpp"
#include "cases/app/study_run.hpp"
#include "cases/app/sweep_run.hpp"
#include "python_options.hpp"
#include "python_results.hpp"
#include "sympathy/continuation/curve_output.hpp"
#include "sympathy/continuation/equilibrium_output.hpp"
#include "sympathy/core/errors.hpp"

namespace sympathy::python {

namespace {

// What Python code does while the engine runs: the progress callback per point and the signal
// check. An exception there is not thrown through the engine: it is kept, the run asked to stop,
// and it is raised once the engine has returned (a KeyboardInterrupt instead ends the run as a
// signal does, with what was computed).
class PythonHooks {
 public:
  explicit PythonHooks(py::object progress) : progress_(std::move(progress)) {}

  bool stop_requested() {
    if (interrupted_ || error_) return true;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) keep(py::error_already_set());
    return interrupted_ || error_;
  }

  // The callback with the point `make` gives (made with the GIL held).
  template <typename Make>
  void report(Make make) {
    if (progress_.is_none()) return;
    call([&] { progress_(make()); });
  }

  // Python code (`f`) run with the GIL held, its exception kept.
  template <typename F>
  void call(F f) {
    if (error_) return;
    py::gil_scoped_acquire gil;
    try {
      f();
    } catch (py::error_already_set& e) {
      keep(std::move(e));
    }
  }

  bool interrupted() const { return interrupted_; }
  // With the GIL held, after the engine returned.
  void raise_kept() {
    if (error_) {
      py::error_already_set e = std::move(*error_);
      error_.reset();
      throw e;
    }
  }

 private:
  void keep(py::error_already_set e) {
    if (e.matches(PyExc_KeyboardInterrupt))
      interrupted_ = true;
    else
      error_ = std::move(e);
  }

  py::object progress_;
  bool interrupted_ = false;
  std::optional<py::error_already_set> error_;
};

// tqdm's bar class where progress=True asks for one: None (after a warning) where tqdm is not
// installed, or where `progress` is not True (a callable, False, None).
py::object tqdm_if_asked(const py::object& progress) {
  if (!py::isinstance<py::bool_>(progress) || !progress.cast<bool>()) return py::none();
  try {
    return py::module_::import("tqdm").attr("tqdm");
  } catch (py::error_already_set&) {
    PyErr_WarnEx(PyExc_UserWarning, "progress=True: tqdm is not installed; no progress bar", 1);
    return py::none();
  }
}

// progress=True: a tqdm bar over the continued parameter's range (advanced by how far each point
// moved along it), when tqdm is installed; without it a warning, once, and no bar. Anything else
// is the callback itself (None: none).
class ProgressBar {
 public:
  // Over a parameter's range: advanced by how far each point (its `value`) moved along it.
  ProgressBar(const py::object& progress, const std::string& what, double from, double to,
              const std::string& parameter) {
    if (!open(progress, py::arg("total") = std::abs(to - from), py::arg("unit") = parameter,
              py::arg("desc") = what + " " + parameter,
              py::arg("bar_format") =
                  "{desc}: {percentage:3.0f}%|{bar}| {n:.4g}/{total:.4g} [{elapsed}]"))
      return;
    auto last = std::make_shared<double>(from);
    py::object b = bar_;
    callback = py::cpp_function([b, last](const py::object& point) {
      const double value = point.attr("value").cast<double>();
      b.attr("update")(std::abs(value - *last));
      *last = value;
    });
  }
  // A count of points (a curve, whose length is not known before): one per point.
  ProgressBar(const py::object& progress, const std::string& what) {
    if (!open(progress, py::arg("unit") = "points", py::arg("desc") = what)) return;
    py::object b = bar_;
    callback = py::cpp_function([b](const py::object&) { b.attr("update")(1); });
  }
  ~ProgressBar() {
    if (!bar_.is_none()) bar_.attr("close")();
  }
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  py::object callback = py::none();  // what the engine's points are reported to

 private:
  // A callable is the callback itself; True a tqdm bar made with `args` (false if none is made:
  // without tqdm, a warning).
  template <typename... Args>
  bool open(const py::object& progress, Args&&... args) {
    if (!py::isinstance<py::bool_>(progress)) {
      callback = progress;
      return false;
    }
    const py::object tqdm = tqdm_if_asked(progress);
    if (tqdm.is_none()) return false;
    bar_ = tqdm(std::forward<Args>(args)...);
    return true;
  }
  py::object bar_ = py::none();
};

// A case file with its parameter set and --set values. Each call loads it again with the call's
// own options (LoadedSystem, as the program does): an equation case file's system comes from the
// cache after the first load.
class Case {
 public:
  // `source`: a path (str or os.PathLike), or a dict of the case file's contents.
  Case(const py::object& source, const std::optional<std::string>& params,
       const std::optional<py::dict>& set) {
    if (py::isinstance<py::dict>(source)) {
      dict_file_ = case_dict_file(toml_text(source.cast<py::dict>()));
      line_.path = *dict_file_;
    } else {
      line_.path = py::str(py::module_::import("os").attr("fspath")(source)).cast<std::string>();
    }
    line_.params = params.value_or("");
    if (set) add_values(*set);
    try {
      loaded_ = load();
    } catch (const InputError& e) {
      // Said here, while the dict's file is alive: the message names its key path.
      throw InputError(dict_message(e.what()));
    }
  }

  const std::string& path() const { return line_.path; }
  std::string params() const { return loaded_->params(); }
  std::vector<std::string> state_names() const { return loaded_->system().state_names(); }
  py::dict parameters() const {
    py::dict d;
    for (const auto& name : loaded_->system().parameter_names())
      d[py::str(name)] = loaded_->value_of(name);
    return d;
  }
  // The same case with more values set on top.
  Case with_values(const py::dict& values) const {
    Case c = *this;
    c.add_values(values);
    c.loaded_ = c.load();
    return c;
  }

  py::object simulate(const py::dict& keywords) const {
    return with_keywords("simulate", [&] { return simulate_with(keywords); });
  }
  py::object simulate_with(const py::dict& keywords) const {
    const app::Arguments args = typed_arguments("simulate", line_, keywords);
    app::SimulationRun run = app::prepare_simulation(args);
    PythonHooks hooks{py::none()};
    std::vector<double> t;
    std::vector<Eigen::VectorXd> states;
    {
      py::gil_scoped_release release;
      app::run_simulation(
          run, [&] { return hooks.stop_requested(); },
          [&](double at, const Eigen::VectorXd& z) {
            t.push_back(at);
            states.push_back(z);
          });
    }
    hooks.raise_kept();
    py::dict fields;
    fields["t"] = vector_array(Eigen::Map<const Eigen::VectorXd>(t.data(), t.size()));
    fields["states"] = matrix_array(states, run.system->dimension());
    fields["state_names"] = run.system->state_names();
    fields["stop"] = !run.failure.empty() ? "integration failed"
                     : run.interrupted    ? "interrupted"
                                          : "end time";
    fields["failure"] = run.failure;
    fields["note"] = run.note;
    return py::module_::import("types").attr("SimpleNamespace")(**fields);
  }

  py::object orbit(const py::dict& keywords) const {
    return with_keywords("orbit", [&] { return orbit_with(keywords); });
  }
  py::object orbit_with(const py::dict& keywords) const {
    const app::Arguments args = typed_arguments("orbit", line_, keywords);
    std::optional<app::OrbitRun> run;
    {
      py::gil_scoped_release release;
      run.emplace(app::run_orbit(args));
    }
    return orbit_result(run->c->system(), run->orbit, run->c->describer());
  }

  py::object continue_branch(const py::dict& keywords, const py::object& progress) const {
    return with_keywords("continue", [&] { return continue_with(keywords, progress); });
  }
  py::object continue_with(const py::dict& keywords, const py::object& progress) const {
    const app::Arguments args = typed_arguments("continue", line_, keywords);
    const app::LoadedSystem c = app::load_system(args);
    app::BranchRequest request = app::continue_request(args, c);
    const app::BranchSource source = c.source(request.start, request.initial, request.start_data);
    const ProgressBar shown(progress, "continue", request.from, request.to, request.parameter);
    PythonHooks hooks(shown.callback);
    request.progress = nullptr;  // progress goes to the callback, not to stderr
    request.on_point = [&](const ContinuationPoint& p) {
      hooks.report([&] { return point_result(p); });
    };
    request.stop_requested = [&] { return hooks.stop_requested(); };
    Branch branch;
    {
      py::gil_scoped_release release;
      branch = app::run_branch(source, request, nullptr);
    }
    hooks.raise_kept();
    return branch_result(branch, c.describer());
  }

  py::object equilibria(const py::dict& keywords, const py::object& progress) const {
    return with_keywords("equilibria", [&] { return equilibria_with(keywords, progress); });
  }
  py::object equilibria_with(const py::dict& keywords, const py::object& progress) const {
    const app::Arguments args = typed_arguments("equilibria", line_, keywords);
    const app::LoadedSystem c = app::load_system(args);
    const app::EquilibriaRequest request = app::equilibria_request(args, c);
    const ProgressBar shown(progress, "equilibria", request.problem.from, request.problem.to,
                            c.system().parameter_names()[request.problem.parameter]);
    PythonHooks hooks(shown.callback);
    EquilibriumCallbacks callbacks;
    callbacks.on_point = [&](const EquilibriumPoint& p) {
      hooks.report([&] {
        py::dict f;
        f["index"] = p.index;
        f["value"] = p.parameter;
        f["unstable"] = p.unstable;
        f["step"] = p.step;
        f["iterations"] = p.iterations;
        return py::module_::import("types").attr("SimpleNamespace")(**f);
      });
    };
    callbacks.stop_requested = [&] { return hooks.stop_requested(); };
    EquilibriumBranch branch;
    {
      py::gil_scoped_release release;
      branch = app::run_equilibria(request, c.system(), callbacks);
    }
    hooks.raise_kept();
    return equilibria_result(branch);
  }

  py::object fit(const py::dict& keywords) const {
    return with_keywords("fit", [&] { return fit_with(keywords); });
  }
  py::object fit_with(const py::dict& keywords) const {
    const app::Arguments args = typed_arguments("fit", line_, keywords);
    const app::FitSetup setup = app::fit_setup(args);
    PythonHooks hooks{py::none()};
    std::optional<app::FitRun> run;
    {
      py::gil_scoped_release release;
      run.emplace(app::run_fit(setup, [&] { return hooks.stop_requested(); }));
    }
    hooks.raise_kept();
    return fit_result(*run->fit.model, run->fit, run->result);
  }

  // The fold or Hopf curve of equilibria from parent=EQUILIBRIA.json: the object sympathy.load
  // gives for its JSON (one reader of the one output, not a second description of it).
  py::object equilibrium_curve_with(const app::Arguments& args, const app::LoadedSystem& c,
                                    const py::object& progress) const {
    const app::EquilibriumCurveRequest r = app::equilibrium_curve_request(args, c);
    const ProgressBar shown(progress, "curve " + r.event_name);
    PythonHooks hooks(shown.callback);
    EquilibriumCurveCallbacks callbacks;
    callbacks.on_point = [&](const EquilibriumCurvePoint& p) {
      hooks.report([&] { return equilibrium_curve_point_result(p); });
    };
    callbacks.stop_requested = [&] { return hooks.stop_requested(); };
    EquilibriumCurve curve;
    {
      py::gil_scoped_release release;
      curve = app::run_equilibrium_curve(r, c.system(), callbacks);
    }
    hooks.raise_kept();
    const py::object parsed =
        py::module_::import("json").attr("loads")(equilibrium_curve_json(curve).dump(
            -1, ' ', false, nlohmann::json::error_handler_t::replace));
    py::object result = py::module_::import("sympathy._load").attr("_object")(parsed);
    result.attr("kind") = "curve";
    return result;
  }

  py::object curve(const py::dict& keywords, const py::object& progress) const {
    return with_keywords("curve", [&] { return curve_with(keywords, progress); });
  }
  py::object curve_with(const py::dict& keywords, const py::object& progress) const {
    const app::Arguments args = typed_arguments("curve", line_, keywords);
    const app::LoadedSystem c = app::load_system(args);
    if (app::wants_equilibrium_curve(args)) return equilibrium_curve_with(args, c, progress);
    app::CurveRequest request = app::curve_request(args, c);
    const ProgressBar shown(progress, "curve " + request.event.text);
    PythonHooks hooks(shown.callback);
    CurveCallbacks callbacks;
    callbacks.on_point = [&](const CurvePoint& p) {
      hooks.report([&] { return curve_point_result(p); });
    };
    callbacks.stop_requested = [&] { return hooks.stop_requested(); };
    if (request.generalized_hopf) {
      // The fold of cycles born at a GH of parent=HOPF_CURVE.json; its `branch` the family that
      // was continued to the fold it starts from.
      GeneralizedHopfFold start;
      BifurcationCurve curve;
      {
        py::gil_scoped_release release;
        curve = app::follow_generalized_hopf_fold(request, c.system(), callbacks, &c.describer(),
                                                  start);
      }
      hooks.raise_kept();
      py::object result = curve_result(curve, &c.describer());
      result.attr("branch") = branch_result(start.family, c.describer());
      return result;
    }
    const app::BranchSource source = c.source(request.branch.start, request.branch.initial);
    request.branch.stop_requested = [&] { return hooks.stop_requested(); };
    Branch parent;
    BifurcationCurve curve;
    {
      py::gil_scoped_release release;
      parent = app::curve_branch(request, c, source, nullptr);
      if (parent.started() && !hooks.interrupted()) {
        const Bifurcation& event = app::find_event(parent, request.event, "--event");
        curve = app::follow_curve(request, c.system(), parent, event, callbacks, &c.describer());
      } else {
        curve.stop = hooks.interrupted() ? StopReason::Interrupted : StopReason::StartFailed;
        curve.stop_reason = "the branch: " + parent.stop_reason;
      }
    }
    hooks.raise_kept();
    py::object result = curve_result(curve, &c.describer());
    result.attr("branch") = branch_result(parent, c.describer());
    return result;
  }

 private:
  // The case loaded as a call loads it (the parameter set and values set checked).
  std::shared_ptr<const app::LoadedSystem> load() const {
    return std::make_shared<const app::LoadedSystem>(with_keywords(
        "orbit", [&] { return app::load_system(typed_arguments("orbit", line_, {})); }));
  }
  void add_values(const py::dict& values) {
    for (const auto& [k, v] : values) {
      Assignment a;
      a.key = k.cast<std::string>();
      a.value = v.cast<double>();
      a.source = "set " + a.key;
      line_.sets.push_back(a);
    }
  }

  CaseLine line_;
  std::shared_ptr<const std::string> dict_file_;  // a dict's TOML file, removed with the last copy
  std::shared_ptr<const app::LoadedSystem> loaded_;
};

// sympathy study: the study file's branches side by side, each as continue_branch computes it,
// their CSV files written to `out` as the program writes them. The branches run on threads of
// their own; this one waits, checking for signals every 50 ms (Python runs its handlers on the
// main thread only, which the branches' own stop checks are not on).
// How many of a run's jobs are done (a study's branches, a map's orbits, basins' runs, a sweep's
// tasks), set from the jobs' threads; `total` once known.
struct JobCount {
  std::atomic<std::size_t> done{0}, total{0};
};

// progress=True: a tqdm bar over the jobs (when tqdm is installed; without it a warning and no
// bar); a callable: called with (done, total) as jobs finish; None: nothing. Called on the calling
// thread only, with the GIL.
class JobsProgress {
 public:
  JobsProgress(const py::object& progress, const std::string& what, const std::string& unit)
      : what_(what), unit_(unit) {
    if (progress.is_none()) return;
    if (!py::isinstance<py::bool_>(progress))
      callback_ = progress;
    else
      tqdm_ = tqdm_if_asked(progress);
  }
  ~JobsProgress() {
    if (!bar_.is_none()) bar_.attr("close")();
  }
  bool wanted() const { return !callback_.is_none() || !tqdm_.is_none(); }
  void report(std::size_t done, std::size_t total) {
    if (done == reported_ && total == total_) return;
    if (!callback_.is_none()) {
      callback_(done, total);
    } else if (!tqdm_.is_none() && total > 0) {
      if (bar_.is_none())
        bar_ = tqdm_(py::arg("total") = total, py::arg("unit") = unit_, py::arg("desc") = what_);
      bar_.attr("update")(done - reported_);
    }
    reported_ = done;
    total_ = total;
  }

 private:
  std::string what_, unit_;
  py::object callback_ = py::none(), tqdm_ = py::none(), bar_ = py::none();
  std::size_t reported_ = 0, total_ = 0;
};

// Runs `work(stop)` on a thread of its own while this one waits without the GIL, checking for
// signals every 50 ms (Python runs its handlers on the main thread only, which the work's own stop
// checks are not on): Ctrl-C sets `stop`, and the work returns what it has. With `progress`, the
// count of jobs done in `count` is reported from this thread as it changes.
template <class Work>
void on_worker_thread(Work&& work, JobsProgress* progress = nullptr, JobCount* count = nullptr) {
  std::atomic<bool> stop{false}, done{false};
  std::exception_ptr failure;
  PythonHooks hooks{py::none()};
  // A callback that raises stops the work (KeyboardInterrupt as Ctrl-C; anything else is raised
  // once the work has returned).
  const auto report = [&] {
    if (progress && count && progress->wanted())
      hooks.call([&] { progress->report(count->done, count->total); });
  };
  {
    py::gil_scoped_release release;
    std::thread worker([&] {
      try {
        work(&stop);
      } catch (...) {
        failure = std::current_exception();
      }
      done = true;
    });
    while (!done) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      if (!done && hooks.stop_requested()) stop = true;
      report();
    }
    worker.join();
    report();
  }
  hooks.raise_kept();
  if (failure) std::rethrow_exception(failure);
}

py::object study(const std::string& path, const py::dict& keywords, const py::object& progress) {
  app::StudyRun run = with_keywords("study", [&] {
    return app::study_run(typed_arguments("study", CaseLine{path, "", {}}, keywords));
  });
  const Stopwatch clock;
  JobsProgress shown(progress, "study", "branches");
  JobCount count;
  count.total = run.job_count();
  app::JobCallbacks callbacks;
  callbacks.finished = [&](std::size_t) { ++count.done; };
  on_worker_thread(
      [&](const std::atomic<bool>* stop) {
        app::run_study_branches(run, stop, callbacks);
        app::run_study_basins(run, stop, {});
      },
      &shown, &count);
  app::write_study_json(run, clock.seconds());  // as the program writes it, beside the CSVs
  py::dict branches;
  for (std::size_t i = 0; i < run.study.branches.size(); ++i) {
    py::object b = branch_result(run.results[i], run.systems[i]->describer());
    b.attr("error") = run.errors[i];
    branches[py::str(run.study.branches[i].name)] = b;
  }
  // The [[equilibria]] entries as sympathy.equilibria returns one, by name.
  py::dict equilibria;
  for (std::size_t k = 0; k < run.study.equilibria.size(); ++k) {
    py::object e = equilibria_result(run.equilibria_results[k]);
    e.attr("error") = run.equilibria_errors[k];
    equilibria[py::str(run.study.equilibria[k].name)] = e;
  }
  py::dict fields;
  fields["title"] = run.study.title;
  fields["parameter"] = run.study.parameter;
  fields["axis"] = run.study.axis;
  fields["branches"] = branches;
  fields["equilibria"] = equilibria;
  fields["equilibria_axis"] = run.equilibria_axis;
  // The [basins] walk as sympathy.load reads it from the study's JSON (None without one).
  fields["basins"] = run.basins ? py::module_::import("sympathy._load")
                                      .attr("_walk")(py::module_::import("json").attr("loads")(
                                          app::study_basins_json(run).dump()))
                                : py::none();
  py::list marks;
  for (const auto& [set, value] : run.marks) {
    py::dict m;
    m["name"] = set;
    m["value"] = value;
    marks.append(m);
  }
  fields["marks"] = marks;
  return py::module_::import("types").attr("SimpleNamespace")(**fields);
}

// sympathy map: the map file's orbits, their branches, event curves and stability grids, and its
// equilibria entries' branches and curves, computed side by side as the program computes them,
// the JSON and CSV files written to `out`.
py::object map(const std::string& path, const py::dict& keywords, const py::object& progress) {
  app::MapRun run = with_keywords("map", [&] {
    const app::Arguments args = typed_arguments("map", CaseLine{path, "", {}}, keywords);
    app::MapRequest request;
    request.path = path;
    request.out = args.text("--out", request.out);
    request.jobs = args.integer("--jobs", request.jobs);
    if (args.has("--accuracy")) request.accuracy = app::accuracy(args);
    return app::prepare_map(request);
  });
  const Stopwatch clock;
  JobsProgress shown(progress, "map", "jobs");
  JobCount count;
  count.total = run.jobs();
  app::JobCallbacks callbacks;
  callbacks.finished = [&](std::size_t) { ++count.done; };
  on_worker_thread([&](const std::atomic<bool>* stop) { app::run_map(run, stop, callbacks); },
                   &shown, &count);
  app::write_map(run, clock.seconds());
  py::list orbits;
  for (std::size_t i = 0; i < run.map.orbits.size(); ++i) {
    const app::MapOrbitResult& r = run.results[i];
    py::dict o;
    o["name"] = run.map.orbits[i].name;
    o["start"] = run.map.orbits[i].start;
    o["branch"] = branch_result(r.branch, run.system->describer());
    py::list curves;
    for (const auto& curve : r.curves) curves.append(curve_result(curve));
    o["curves"] = curves;
    if (r.grid.first.empty()) {
      o["grid"] = py::none();
    } else {
      py::dict g;
      g["first"] = r.grid.first;
      g["second"] = r.grid.second;
      g["unstable_count"] = r.grid.unstable_count;
      o["grid"] = py::module_::import("types").attr("SimpleNamespace")(**g);
    }
    o["error"] = r.error;
    o["seconds"] = r.seconds;
    orbits.append(py::module_::import("types").attr("SimpleNamespace")(**o));
  }
  py::dict fields;
  fields["name"] = run.map.name;
  fields["title"] = run.map.title;
  fields["first"] = run.map.first.parameter;
  fields["second"] = run.map.second.parameter;
  fields["json"] = run.json_path;
  fields["window"] = py::make_tuple(py::make_tuple(run.map.first.from, run.map.first.to),
                                    py::make_tuple(run.map.second.from, run.map.second.to));
  fields["orbits"] = orbits;
  // The equilibria entries (branch, curves) as sympathy.load reads them from the JSON just
  // written: one reader of that shape.
  fields["equilibria"] =
      py::module_::import("sympathy._load").attr("load")(run.json_path).attr("equilibria");
  // The case's parameter sets marked (as the JSON has them: name, first, second, in_plane, ...).
  fields["marks"] = py::module_::import("json").attr("loads")(run.marks.dump());
  return py::module_::import("types").attr("SimpleNamespace")(**fields);
}

// sympathy basins and sympathy sweep on this machine's threads: the files written as the program
// writes them; returns the JSON's path and whether Ctrl-C interrupted the tasks (the package reads
// the JSON).
template <class Run>
py::tuple journaled(const std::string& command, const std::string& unit, const std::string& path,
                    const py::dict& keywords, const py::object& progress, Run run) {
  const app::Arguments args = typed_arguments(command, CaseLine{path, "", {}}, keywords);
  app::JournaledOutcome outcome;
  JobsProgress shown(progress, command, unit);
  JobCount count;
  const auto recorded = [&](std::size_t done, std::size_t total) {
    count.total = total;
    count.done = done;
  };
  with_keywords(command, [&] {
    on_worker_thread([&](const std::atomic<bool>* stop) { outcome = run(args, stop, recorded); },
                     &shown, &count);
    return 0;
  });
  return py::make_tuple(outcome.json_path, outcome.interrupted);
}

py::tuple basins(const std::string& path, const py::dict& keywords, const py::object& progress) {
  return journaled("basins", "runs", path, keywords, progress, app::run_basins_here);
}

py::tuple sweep(const std::string& path, const py::dict& keywords, const py::object& progress) {
  return journaled("sweep", "tasks", path, keywords, progress, app::run_sweep_here);
}

}  // namespace

}  // namespace sympathy::python

PYBIND11_MODULE(_core, m) {
  namespace py = pybind11;
  using namespace sympathy;
  using sympathy::python::Case;
  m.doc() =
      "sympathy's engine, for the package sympathy (python/sympathy/__init__.py), which builds its "
      "functions' signatures from command_options and checks their keywords' types: every call "
      "here takes a dict of checked keywords.";
  // Every result holds NumPy arrays: without NumPy the module says so at import, not after a
  // computation has run to its end.
  try {
    py::module_::import("numpy");
  } catch (py::error_already_set& e) {
    throw py::import_error(
        std::string("sympathy needs NumPy for its results, and it cannot be imported (") +
        e.what() +
        "); expected NumPy installed: apt-get install python3-numpy, or pip install numpy");
  }
  // Bad input (a case file, an option): ValueError, with the program's message (a case dict's
  // key path where a file and line would be).
  static py::exception<InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      input_error(sympathy::python::dict_message(e.what()).c_str());
    }
  });
  py::register_exception<OutputError>(m, "OutputError", PyExc_OSError);
  m.def("commands", &sympathy::python::python_commands);
  m.def("command_options", &sympathy::python::option_table, py::arg("command"));
  m.def("study", &sympathy::python::study, py::arg("path"), py::arg("keywords"),
        py::arg("progress") = py::none());
  m.def("map", &sympathy::python::map, py::arg("path"), py::arg("keywords"),
        py::arg("progress") = py::none());
  m.def("basins", &sympathy::python::basins, py::arg("path"), py::arg("keywords"),
        py::arg("progress") = py::none());
  m.def("sweep", &sympathy::python::sweep, py::arg("path"), py::arg("keywords"),
        py::arg("progress") = py::none());
  py::class_<Case>(m, "Case")
      .def(py::init<const py::object&, const std::optional<std::string>&,
                    const std::optional<py::dict>&>(),
           py::arg("source"), py::arg("params") = py::none(), py::arg("set") = py::none())
      .def_property_readonly("path", &Case::path)
      .def_property_readonly("params", &Case::params)
      .def_property_readonly("parameters", &Case::parameters)
      .def_property_readonly("state_names", &Case::state_names)
      .def("with_values", &Case::with_values, py::arg("values"))
      .def("simulate", &Case::simulate, py::arg("keywords"))
      .def("orbit", &Case::orbit, py::arg("keywords"))
      .def("continue_branch", &Case::continue_branch, py::arg("keywords"),
           py::arg("progress") = py::none())
      .def("equilibria", &Case::equilibria, py::arg("keywords"), py::arg("progress") = py::none())
      .def("fit", &Case::fit, py::arg("keywords"))
      .def("curve", &Case::curve, py::arg("keywords"), py::arg("progress") = py::none());
}
