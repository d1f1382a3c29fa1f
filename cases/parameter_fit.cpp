#include "sympathy/cases/parameter_fit.hpp"
#include "sympathy/cases/names.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/cases/platform_model.hpp"
#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

int index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  return it == names.end() ? -1 : static_cast<int>(it - names.begin());
}

// A parameter that may take either sign (the rest are physically positive or non-negative).
bool signed_parameter(const std::string& name) {
  return split_index(name).first == "angle";
}

double rms(const Eigen::VectorXd& v) {
  return v.size() ? std::sqrt(v.squaredNorm() / static_cast<double>(v.size())) : 0.0;
}

std::string describe_model(const ModelSpec& spec, bool locked) {
  const int n = static_cast<int>(spec.metronomes.size());
  std::ostringstream s;
  if (locked)
    s << "the platform alone (" << spec.directions << "-D), " << n
      << (n == 1 ? " metronome" : " metronomes") << " locked to it";
  else
    s << n << (n == 1 ? " metronome" : " metronomes") << " on a " << spec.directions
      << "-D platform";
  return s.str();
}

}  // namespace

Range parse_range(const std::string& text, const std::string& option) {
  Range r;
  r.source = option + " " + text;
  const auto eq = text.find('=');
  const auto colon = eq == std::string::npos ? std::string::npos : text.find(':', eq);
  auto number = [&](const std::string& s, double& v) {
    const auto x = finite_number(s);
    if (x) v = *x;
    return x.has_value();
  };
  if (eq == std::string::npos || eq == 0 || colon == std::string::npos ||
      !number(text.substr(eq + 1, colon - eq - 1), r.lower) ||
      !number(text.substr(colon + 1), r.upper))
    throw InputError(r.source + ": expected NAME=LO:HI with two finite numbers");
  if (!(r.lower < r.upper)) throw InputError(r.source + ": expected LO < HI");
  r.name = text.substr(0, eq);
  return r;
}

FitModel metronome_fit_model(const CaseFile& file, const ModelSpec& spec, bool locked_pendula) {
  FitModel m;
  m.description = describe_model(spec, locked_pendula);
  m.case_path = file.path();
  if (locked_pendula) {
    m.owned = std::make_unique<PlatformModel>(spec);
  } else {
    if (spec.escapement == Escapement::Impulsive)
      throw InputError(file.path() +
                       ": escapement \"impulsive\" has no derivatives, which the fit needs; "
                       "expected \"half\" or \"double\" (e.g. a copy of the case file)");
    m.owned = std::make_unique<MetronomeModel>(spec);
  }
  m.system = m.owned.get();
  m.values = m.system->default_parameters();
  m.initial = Eigen::VectorXd::Zero(m.system->dimension());
  m.initial_source = "default";
  m.domain = [](const std::string& name, double) {
    ParameterDomain d;
    if (signed_parameter(name)) {  // a direction, in degrees
      d.positive = false;
      d.scale = 10.0;
      d.half_width = 45.0;
    } else {
      d.lower = 0.0;
    }
    return d;
  };
  if (locked_pendula)
    m.why_not_a_parameter = [spec](const std::string& name) {
      return spec.has_parameter(name) ? "with --locked-pendula the model is the platform alone, "
                                        "where '" +
                                            name + "' does not enter"
                                      : std::string();
    };
  return m;
}

FitModel equation_fit_model(const EquationCase& file, const OdeSystem& system,
                            const ParameterValues& values) {
  FitModel m;
  m.description = "the equations of " + file.path();
  m.case_path = file.path();
  m.system = &system;
  m.values = values;
  m.initial = file.initial_state(nullptr);
  m.initial_source = "[states]";
  const auto parameters = file.system().parameters;
  m.domain = [parameters](const std::string& name, double start) {
    ParameterDomain d;
    for (const auto& p : parameters) {
      if (p.name != name) continue;
      if (p.min) d.lower = *p.min;
      if (p.max) d.upper = *p.max;
      d.positive = p.min && *p.min >= 0.0 && start > 0.0;
      d.scale = start != 0.0 ? std::abs(start) : 1.0;
      d.half_width = 10.0 * d.scale;
    }
    return d;
  };
  return m;
}

PreparedFit prepare_fit(const CaseFile& file, const ModelSpec& spec, const FitRequest& request) {
  return prepare_fit(metronome_fit_model(file, spec, request.locked_pendula), request);
}

PreparedFit prepare_fit(FitModel fm, const FitRequest& request) {
  PreparedFit fit;
  fit.model_description = fm.description;
  fit.owned = std::move(fm.owned);
  fit.model = fm.system;
  const OdeSystem& model = *fit.model;
  const auto parameters = model.parameter_names();
  const auto states = model.state_names();
  const int n = model.dimension();

  // Free parameters and initial components.
  if (request.free.empty() && request.free_initial.empty())
    throw InputError("--free: expected one or more parameter names (" + join(parameters) + ")");
  for (std::size_t j = 0; j < request.free.size(); ++j) {
    const std::string& name = request.free[j];
    if (std::count(request.free.begin(), request.free.begin() + j, name))
      throw InputError("--free " + name + ": given twice; expected each parameter once");
    if (index_of(parameters, name) < 0) {
      const std::string why = fm.why_not_a_parameter ? fm.why_not_a_parameter(name) : "";
      if (!why.empty())
        throw InputError("--free " + name + ": " + why + "; expected one of: " + join(parameters));
      throw InputError("--free " + name + ": the case " + fm.case_path + " has no parameter '" +
                       name + "'; expected one of: " + join(parameters));
    }
  }
  for (std::size_t j = 0; j < request.free_initial.size(); ++j) {
    const std::string& name = request.free_initial[j];
    if (std::count(request.free_initial.begin(), request.free_initial.begin() + j, name))
      throw InputError("--free-initial " + name + ": given twice; expected each state once");
    if (index_of(states, name) < 0)
      throw InputError("--free-initial " + name + ": not a state of " + fit.model_description +
                       "; expected one of: " + join(states));
  }

  // The recording.
  const std::string system_text = request.locked_pendula
                                      ? "the platform with locked pendula (--locked-pendula)"
                                      : "the case " + fm.case_path;
  fit.recording = read_recording(request.data, states, system_text);
  const Recording& rec = fit.recording;
  const int m = static_cast<int>(rec.columns.size());

  // Initial state: a named start and --initial for the unrecorded states, the first row for the
  // recorded ones.
  Eigen::VectorXd z0 = fm.initial;
  fit.initial_source.assign(n, fm.initial_source);
  if (request.start) {
    for (const auto& [name, value] : request.start->values) {
      const int c = index_of(states, name);
      if (c < 0) continue;  // a pendulum's angle when the pendula are locked
      z0[c] = value;
      fit.initial_source[c] = "--start " + request.start->name;
    }
  }
  for (const auto& a : request.initial) {
    const int c = index_of(states, a.key);
    if (c < 0)
      throw InputError(a.source + ": unknown state '" + a.key +
                       "'; expected one of: " + join(states));
    if (std::count(rec.columns.begin(), rec.columns.end(), a.key))
      throw InputError(a.source + ": '" + a.key + "' is recorded in " + rec.path +
                       ", so its initial value is the first row's; expected an unrecorded state "
                       "(use --free-initial " +
                       a.key + " to fit it)");
    z0[c] = a.value;
    fit.initial_source[c] = "--initial";
  }
  for (int k = 0; k < m; ++k) {
    z0[rec.components[k]] = rec.values(0, k);
    fit.initial_source[rec.components[k]] = "data";
  }

  // Residual scales: the noise level if given, else the RMS of the recorded column.
  Eigen::VectorXd scale(m);
  for (int k = 0; k < m; ++k) {
    const double r = rms(rec.values.col(k));
    scale[k] = r > 0.0 ? r : 1.0;
  }
  for (const auto& a : request.sigma) {
    const int k = index_of(rec.columns, a.key);
    if (k < 0)
      throw InputError(a.source + ": '" + a.key + "' is not a column of " + rec.path +
                       "; expected one of: " + join(rec.columns));
    if (!(a.value > 0.0)) throw InputError(a.source + ": expected a positive noise level");
    scale[k] = a.value;
  }

  auto range_of = [&](const std::string& name) -> const Range* {
    const Range* found = nullptr;
    for (const auto& r : request.ranges)
      if (r.name == name) found = &r;
    return found;
  };
  for (const auto& r : request.ranges) {
    const bool is_parameter = std::count(request.free.begin(), request.free.end(), r.name) > 0;
    const bool is_initial =
        std::count(request.free_initial.begin(), request.free_initial.end(), r.name) > 0;
    if (!is_parameter && !is_initial)
      throw InputError(r.source + ": '" + r.name +
                       "' is not fitted; expected a name given to --free or --free-initial");
  }

  TrajectoryFitProblem& pb = fit.problem;
  pb.times = rec.times;
  pb.observed = rec.components;
  pb.values = rec.values;
  pb.column_scale = scale;
  pb.initial_state = z0;
  pb.parameter_values = fm.values;
  for (const auto& name : request.free) {
    FreeParameter f;
    f.index = model.parameter_index(name);
    const double start = model.parameter(pb.parameter_values, f.index);
    const Range* range = range_of(name);
    const ParameterDomain domain = fm.domain(name, start);
    if (!domain.positive) {
      f.logarithmic = false;
      f.scale = domain.scale;
      f.lower = domain.lower;
      f.upper = domain.upper;
      f.search_lower = std::max(domain.lower, start - domain.half_width);
      f.search_upper = std::min(domain.upper, start + domain.half_width);
    } else {
      if (!(start > 0.0))
        throw InputError("--free " + name + ": its starting value is " + format_double(start) +
                         "; expected a positive start for a positive parameter (--set " + name +
                         "=VALUE)");
      f.logarithmic = true;
      f.lower = std::max(0.0, domain.lower);
      f.upper = domain.upper;
      f.search_lower = std::max(f.lower, start / request.search_factor);
      f.search_upper = std::min(f.upper, start * request.search_factor);
    }
    if (range) {
      if (f.logarithmic && !(range->lower > 0.0))
        throw InputError(range->source + ": expected LO > 0 for the positive parameter '" + name +
                         "'");
      if (!(range->lower <= start && start <= range->upper))
        throw InputError(range->source + ": the starting value " + format_double(start) + " of '" +
                         name + "' is outside; expected LO <= start <= HI");
      f.lower = f.search_lower = range->lower;
      f.upper = f.search_upper = range->upper;
    }
    pb.parameters.push_back(f);
    fit.unknowns.push_back(name);
  }
  for (const auto& name : request.free_initial) {
    FreeInitial f;
    f.component = index_of(states, name);
    // Scale: the recorded column's RMS; a velocity whose position is recorded, the RMS of that
    // position's rate of change; else the magnitude of its start, at least 1e-3.
    const int k = index_of(rec.columns, name);
    double s = k >= 0 ? scale[k] : 0.0;
    if (k < 0 && name.size() > 1 && name[0] == 'v') {
      const int kp = index_of(rec.columns, name.substr(1));
      if (kp >= 0 && rec.samples() > 1) {
        Eigen::VectorXd rate(rec.samples() - 1);
        for (int i = 0; i + 1 < rec.samples(); ++i)
          rate[i] = (rec.values(i + 1, kp) - rec.values(i, kp)) / (rec.times[i + 1] - rec.times[i]);
        s = rms(rate);
      }
    }
    if (!(s > 0.0)) s = std::max(std::abs(z0[f.component]), 1e-3);
    f.scale = s;
    f.search_lower = z0[f.component] - 2.0 * s;
    f.search_upper = z0[f.component] + 2.0 * s;
    if (const Range* range = range_of(name)) {
      if (!(range->lower <= z0[f.component] && z0[f.component] <= range->upper))
        throw InputError(range->source + ": the starting value " + format_double(z0[f.component]) +
                         " of '" + name + "' is outside; expected LO <= start <= HI");
      f.search_lower = range->lower;
      f.search_upper = range->upper;
    }
    pb.initial.push_back(f);
    fit.unknowns.push_back(name + "(0)");
  }

  const int residuals = residual_count(pb);
  const int unknowns = static_cast<int>(fit.unknowns.size());
  if (residuals <= unknowns)
    throw InputError(rec.path + ": " + std::to_string(rec.samples()) + " samples of " +
                     join(rec.columns) + " give " + std::to_string(residuals) +
                     " residuals (the first row fixes the initial state); fitting " +
                     std::to_string(unknowns) + " unknowns (" + join(fit.unknowns) +
                     ") needs more than " + std::to_string(unknowns) + ": expected more samples");
  return fit;
}

}  // namespace sympathy
