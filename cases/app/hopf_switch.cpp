#include "cases/app/hopf_switch.hpp"

#include "cases/app/json_reader.hpp"

#include <algorithm>
#include <cmath>
#include <regex>

#include "sympathy/continuation/hopf.hpp"
#include "sympathy/core/csv.hpp"

namespace sympathy::app {

std::optional<int> parse_hopf_name(const std::string& text, const std::string& option) {
  if (text.rfind("HB", 0) != 0) return std::nullopt;
  const std::string number = text.substr(2);
  if (number.empty() || number.size() > 8 ||
      number.find_first_not_of("0123456789") != std::string::npos || std::stoi(number) < 1)
    throw InputError(option + " " + text +
                     ": expected HB followed by a positive number (e.g. HB1)");
  return std::stoi(number);
}

EquilibriumBranch read_equilibria_json(const std::string& path, const OdeSystem& system) {
  const JsonReader in(path, "equilibria written by sympathy equilibria --json");
  auto key = [&](const nlohmann::json& x, const std::string& name,
                 const std::string& where) -> const nlohmann::json& {
    return in.key(x, name, where);
  };
  auto numbers = [&](const nlohmann::json& x, const std::string& where, int size) {
    return in.numbers(x, where, size);
  };
  const int n = system.dimension();
  return in.read([&](const nlohmann::json& j) {
    EquilibriumBranch b;
    if (key(j, "kind", path) != "equilibria")
      throw InputError(path +
                       ": key 'kind': expected \"equilibria\" (written by sympathy "
                       "equilibria --json)");
    b.parameter_name = key(j, "parameter", path).get<std::string>();
    try {
      b.parameter = system.parameter_index(b.parameter_name);
    } catch (const std::invalid_argument& e) {
      throw InputError(path + ": key 'parameter': " + e.what());
    }
    b.start_values = numbers(key(j, "parameter_values", path), path + ": key 'parameter_values'",
                             system.parameter_values_size());
    if (j.contains("points"))
      for (const nlohmann::json& q : j["points"]) {
        EquilibriumPoint pt;
        pt.index = q.at("index").get<int>();
        pt.parameter = q.at("value").get<double>();
        pt.state = numbers(q.at("state"), path + ": points[].state", n);
        b.points.push_back(std::move(pt));
      }
    const auto& events = key(j, "events", path);
    for (std::size_t i = 0; i < events.size(); ++i) {
      const std::string where = path + ": events[" + std::to_string(i) + "]";
      EquilibriumEvent e;
      const std::string type = key(events[i], "type", where).get<std::string>();
      // The names to_string writes, read back.
      bool known = false;
      for (const auto t : {EquilibriumEventType::Fold, EquilibriumEventType::BranchPoint,
                           EquilibriumEventType::Hopf, EquilibriumEventType::UserPoint})
        if (to_string(t) == type) {
          e.type = t;
          known = true;
        }
      if (!known)
        throw InputError(where + ": key 'type': \"" + type +
                         "\"; expected LP, BP, HB or UZ (written by sympathy equilibria --json)");
      e.parameter = key(events[i], "value", where).get<double>();
      e.state = numbers(key(events[i], "state", where), where + ".state", n);
      // The branch's direction there (written since BP switching; a switch without it takes
      // the branching equation's root least parallel to nothing in particular).
      if (events[i].contains("tangent") && events[i]["tangent"].size() == std::size_t(n + 1))
        e.tangent = numbers(events[i]["tangent"], where + ".tangent", n + 1);
      if (e.type == EquilibriumEventType::Hopf) {
        const auto& h = key(events[i], "hopf", where);
        HopfPoint hp;
        hp.parameter = e.parameter;
        hp.state = e.state;
        hp.values = system.with_parameter(b.start_values, b.parameter, e.parameter);
        hp.omega = key(h, "omega", where + ".hopf").get<double>();
        hp.period = key(h, "period", where + ".hopf").get<double>();
        hp.uncertainty = key(h, "uncertainty", where + ".hopf").get<double>();
        const Eigen::VectorXd re = numbers(key(h, "eigenvector_re", where), where + ".hopf", n);
        const Eigen::VectorXd im = numbers(key(h, "eigenvector_im", where), where + ".hopf", n);
        hp.eigenvector = re.cast<std::complex<double>>() +
                         std::complex<double>(0, 1) * im.cast<std::complex<double>>();
        if (h.contains("lyapunov")) hp.lyapunov = h.at("lyapunov").get<double>();
        if (h.contains("c1")) {
          const Eigen::VectorXd c1 = numbers(h.at("c1"), where + ".hopf.c1", 2);
          hp.c1 = std::complex<double>(c1[0], c1[1]);
        }
        e.hopf = hp;
      }
      b.events.push_back(std::move(e));
    }
    return b;
  });
}

Branch run_hopf_branch(const BranchSource& source, const BranchRequest& request, int ordinal,
                       const ContinuationCallbacks& callbacks) {
  const OdeSystem& system = source.system;
  const int parameter = system.parameter_index(request.parameter);
  EquilibriumBranch own;  // read or computed here, unless the request holds them
  if (!request.parent_equilibria && !request.parent_path.empty()) {
    own = read_equilibria_json(request.parent_path, system);
    if (own.parameter_name != request.parameter)
      throw InputError("--parent " + request.parent_path + ": equilibria in " + own.parameter_name +
                       "; expected them in --param " + request.parameter);
  } else if (!request.parent_equilibria) {
    EquilibriumProblem problem;
    problem.parameter = parameter;
    problem.values = source.values;
    problem.from = request.from;
    problem.to = request.to;
    problem.at = request.at;
    problem.start_state = source.start_state;
    EquilibriumCallbacks cb;
    cb.stop_requested = callbacks.stop_requested;
    if (request.progress)
      cb.on_event = [&](const EquilibriumEvent& e) {
        std::fprintf(request.progress, "  (equilibria) >> %s at %s = %.10g\n",
                     to_string(e.type).c_str(), request.parameter.c_str(), e.parameter);
      };
    own = continue_equilibria(system, problem, {}, cb);
  }
  const EquilibriumBranch& parent = request.parent_equilibria ? *request.parent_equilibria : own;
  Branch born;
  born.parameter_name = request.parameter;
  born.parameter = parameter;
  born.state_names = system.state_names();
  if (!parent.started()) {
    born.stop = StopReason::StartFailed;
    born.stop_reason = "no equilibria to switch at: " + parent.stop_reason;
    return born;
  }
  int seen = 0;
  const EquilibriumEvent* hopf = nullptr;
  std::string list;
  for (const auto& e : parent.events) {
    if (e.type != EquilibriumEventType::Hopf) continue;
    list += (list.empty() ? "" : ", ") + std::string("HB") + std::to_string(seen + 1) + " at " +
            format_double(e.parameter);
    if (++seen == ordinal) hopf = &e;
  }
  if (!hopf || !hopf->hopf)
    throw InputError("--switch-at " + request.switch_at +
                     ": the equilibria have no such Hopf point; they have " +
                     (list.empty() ? std::string("none") : list));
  if (request.progress)
    std::fprintf(request.progress, "  switching at %s: %s = %.10g (%s)\n",
                 request.switch_at.c_str(), request.parameter.c_str(), hopf->parameter,
                 describe_criticality(hopf->hopf->lyapunov).c_str());
  return run_hopf_family(system, request, *hopf->hopf, request.switch_at, callbacks);
}

Branch run_hopf_family(const OdeSystem& system, const BranchRequest& request, const HopfPoint& hopf,
                       const std::string& name, const ContinuationCallbacks& callbacks) {
  const int parameter = system.parameter_index(request.parameter);
  Branch born;
  born.parameter_name = request.parameter;
  born.parameter = parameter;
  born.state_names = system.state_names();
  ContinuationOptions window = request.continuation;
  window.lower = std::min(request.from, request.to);
  window.upper = std::max(request.from, request.to);
  try {
    born = continue_from_hopf(system, parameter, hopf, window, callbacks, request.hopf_start);
  } catch (const std::runtime_error& e) {
    born.stop = StopReason::StartFailed;
    born.stop_reason = "no family born at " + name + ": " + e.what();
  }
  return born;
}

bool holds_hopf_curve(const std::string& path) {
  const JsonReader file(path, "a branch, curve or equilibria JSON the program wrote");
  const nlohmann::json& j = file.root();
  return j.is_object() && j.contains("of") && j["of"] == "equilibria" && j.contains("kind") &&
         j["kind"] == "HB";
}

HopfPoint read_hopf_curve_point(const SavedStart& start, const OdeSystem& system, int parameter) {
  const JsonReader in(start.path, "a Hopf curve of equilibria written by sympathy curve --json");
  const int n = system.dimension();
  return in.read([&](const nlohmann::json& j) {
    const auto index_of = [&](const std::string& key) {
      const std::string name = in.key(j, key, start.path).get<std::string>();
      try {
        return system.parameter_index(name);
      } catch (const std::invalid_argument& e) {
        throw InputError(start.path + ": key '" + key + "': " + e.what());
      }
    };
    const int first = index_of("first"), second = index_of("second");
    const ParameterValues base =
        in.numbers(in.key(j, "parameter_values", start.path),
                   start.path + ": key 'parameter_values'", system.parameter_values_size());
    std::size_t digits = 0;
    int wanted = 0;
    try {
      wanted = std::stoi(start.what, &digits);
    } catch (const std::exception&) {
      digits = 0;
    }
    if (digits == 0 || digits != start.what.size())
      throw InputError("--from-point " + start.what + ": " + start.path +
                       " is a Hopf curve of equilibria; expected the index of one of its points");
    for (const nlohmann::json& q : in.key(j, "points", start.path)) {
      if (q.at("index").get<int>() != wanted) continue;
      const std::string where = start.path + ": point " + start.what;
      if (q.at("neutral_saddle").get<bool>() || !q.at("omega").is_number())
        throw InputError("--from-point " + start.what + ": " + where +
                         " is a neutral saddle (real eigenvalues +-k): no orbits are born there");
      ParameterValues values =
          system.with_parameter(system.with_parameter(base, first, q.at("first").get<double>()),
                                second, q.at("second").get<double>());
      const Eigen::VectorXd state = in.numbers(q.at("state"), where + ".state", n);
      HopfPoint h = describe_hopf(system, values, state, q.at("omega").get<double>());
      h.parameter = system.parameter(values, parameter);
      return h;
    }
    throw InputError("--from-point " + start.what + ": " + start.path +
                     " has no point of that index");
  });
}

bool holds_curve_of_equilibria(const std::string& path) {
  const JsonReader file(path, "a branch, curve or equilibria JSON the program wrote");
  const nlohmann::json& j = file.root();
  return j.is_object() && j.contains("of") && j["of"] == "equilibria";
}

CurveOfEquilibriaEvent read_curve_of_equilibria_event(const std::string& path,
                                                      const std::string& text,
                                                      const std::string& option,
                                                      const OdeSystem& system) {
  std::smatch m;
  if (!std::regex_match(text, m, std::regex("(BT|CP|GH|ZH|HH)([1-9][0-9]{0,5})")))
    throw InputError(option + " " + text + ": " + path +
                     " is a curve of equilibria; expected one of its codimension-two points, BT, "
                     "CP, GH, ZH or HH followed by its number along the curve (e.g. BT1)");
  const std::string type = m[1];
  const int wanted = std::stoi(m[2]);
  const JsonReader in(path, "a curve of equilibria written by sympathy curve --json");
  const int n = system.dimension();
  return in.read([&](const nlohmann::json& j) {
    const auto index_of = [&](const std::string& key) {
      const std::string name = in.key(j, key, path).get<std::string>();
      try {
        return system.parameter_index(name);
      } catch (const std::invalid_argument& e) {
        throw InputError(path + ": key '" + key + "': " + e.what());
      }
    };
    CurveOfEquilibriaEvent out;
    CodimensionTwoPoint& p = out.point;
    p.type = type;
    p.on = in.key(j, "kind", path).get<std::string>() == "HB" ? EquilibriumEventType::Hopf
                                                              : EquilibriumEventType::Fold;
    p.first = index_of("first");
    p.second = index_of("second");
    const ParameterValues base =
        in.numbers(in.key(j, "parameter_values", path), path + ": key 'parameter_values'",
                   system.parameter_values_size());
    for (const nlohmann::json& q : in.key(j, "points", path)) {
      const std::string where = path + ": a point";
      p.state_scale = std::max(
          p.state_scale,
          in.numbers(in.key(q, "state", where), where + ".state", n).lpNorm<Eigen::Infinity>());
      const nlohmann::json& kappa = in.key(q, "kappa", where);
      if (kappa.is_number()) p.kappa_scale = std::max(p.kappa_scale, std::abs(kappa.get<double>()));
    }
    int seen = 0;
    for (const nlohmann::json& e : in.key(j, "events", path)) {
      if (in.key(e, "type", path + ": an event").get<std::string>() != type || ++seen != wanted)
        continue;
      const std::string where = path + ": event " + text;
      if (!in.key(e, "located", where).get<bool>())
        throw InputError(option + " " + text + ": " + where +
                         " was not located (its note: " + e.value("note", std::string()) + ")");
      for (const auto& [name, value] : in.key(e, "coefficients", where).items())
        if (value.is_number()) out.coefficients.emplace_back(name, value.get<double>());
      const nlohmann::json& point = in.key(e, "point", where);
      p.state = in.numbers(in.key(point, "state", where + ".point"), where + ".point.state", n);
      const nlohmann::json& kappa = in.key(point, "kappa", where + ".point");
      p.kappa = kappa.is_number() ? kappa.get<double>() : std::nan("");
      p.values = system.with_parameter(
          system.with_parameter(base, p.first, in.key(e, "first", where).get<double>()), p.second,
          in.key(e, "second", where).get<double>());
      return out;
    }
    throw InputError(option + " " + text + ": " + path + " has " + std::to_string(seen) + " " +
                     type + " point" + (seen == 1 ? "" : "s"));
  });
}

GeneralizedHopfPoint read_generalized_hopf(const std::string& path, const std::string& text,
                                           const std::string& option, const OdeSystem& system) {
  if (text.rfind("GH", 0) != 0)
    throw InputError(option + " " + text + ": " + path +
                     " is a Hopf curve of equilibria; expected GH followed by a positive number "
                     "(e.g. GH1): only at a generalized Hopf point is a fold of cycles born");
  const CurveOfEquilibriaEvent e = read_curve_of_equilibria_event(path, text, option, system);
  GeneralizedHopfPoint gh;
  gh.at = e.point;
  gh.l2 = std::nan("");
  for (const auto& [name, value] : e.coefficients)
    if (name == "l2") gh.l2 = value;
  if (!std::isfinite(gh.l2))
    throw InputError(option + " " + text + ": " + path + ": event " + text +
                     " has no l2 (the system gave no fifth derivatives): which side has the fold "
                     "of cycles is not known");
  return gh;
}

}  // namespace sympathy::app
