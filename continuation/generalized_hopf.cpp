#include "sympathy/continuation/generalized_hopf.hpp"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

#include "sympathy/core/csv.hpp"
#include "sympathy/core/text.hpp"

namespace sympathy {

namespace {

std::string at_values(const OdeSystem& system, const ParameterValues& values, int first,
                      int second) {
  const auto names = system.parameter_names();
  return names[first] + " = " + format_double(system.parameter(values, first)) + ", " +
         names[second] + " = " + format_double(system.parameter(values, second));
}

}  // namespace

GeneralizedHopfFold fold_of_cycles_from_generalized_hopf(const OdeSystem& system,
                                                         const GeneralizedHopfPoint& gh,
                                                         const GeneralizedHopfOptions& options,
                                                         const ContinuationCallbacks& family,
                                                         const CurveCallbacks& callbacks) {
  const int count = system.parameter_count();
  if (gh.at.first < 0 || gh.at.first >= count || gh.at.second < 0 || gh.at.second >= count ||
      gh.at.first == gh.at.second)
    throw std::invalid_argument("generalized Hopf: expected two different parameters");
  if (!std::isfinite(gh.l2) || gh.l2 == 0.0)
    throw std::invalid_argument(
        "generalized Hopf: no second Lyapunov coefficient l2 (it needs f's fifth derivatives, "
        "which a system written as a template gives), or l2 = 0: which side of the point has "
        "the fold of cycles is not known");
  const double omega = gh.at.kappa > 0.0 ? std::sqrt(gh.at.kappa) : 0.0;
  if (!(omega > 0.0) || gh.at.state.size() != system.dimension())
    throw std::invalid_argument("generalized Hopf: the point has no frequency or no state");
  if (auto wrong = options.curve.validate())
    throw std::invalid_argument("generalized Hopf: " + wrong->message());
  if (auto wrong = options.start.validate())
    throw std::invalid_argument("generalized Hopf: " + wrong->message());
  const std::string where = at_values(system, gh.at.values, gh.at.first, gh.at.second);

  // 1. The Hopf point whose l1 puts the fold at the amplitude asked for: r^2 = -l1 / (2 l2),
  // r the normal form's radius, the orbit's amplitude along Re q 2 r |Re q|_inf (|q| = 1).
  const HopfPoint centre = describe_hopf(system, gh.at.values, gh.at.state, omega);
  const double scale = std::max(1.0, gh.at.state.lpNorm<Eigen::Infinity>());
  const double amplitude = options.amplitude > 0.0 ? options.amplitude : 0.1 * scale;
  const double re_q = centre.eigenvector.real().lpNorm<Eigen::Infinity>();
  const double radius = amplitude / (2.0 * re_q);
  const double l1_wanted = -2.0 * gh.l2 * radius * radius;
  const double p1 = system.parameter(gh.at.values, gh.at.first),
               p2 = system.parameter(gh.at.values, gh.at.second);
  const double width = options.curve.second_upper - options.curve.second_lower;
  const double step1 = 1e-4 * std::max(1.0, std::abs(p1));
  std::string why;
  const auto hopf_at = [&](double delta) {
    const ParameterValues v = system.with_parameter(gh.at.values, gh.at.second, p2 + delta);
    auto h = hopf_point_near(system, gh.at.first, v, gh.at.state, omega, step1, why);
    if (!h || !h->lyapunov)
      throw std::runtime_error("generalized Hopf at " + where + ": no Hopf point with l1 at " +
                               system.parameter_names()[gh.at.second] + " = " +
                               format_double(p2 + delta) + (h ? "" : ": " + why));
    return *h;
  };
  // l1 is linear in the second parameter near GH: its slope from a small step, then the step
  // that gives l1_wanted, refined twice by the secant through GH (l1 = 0 there).
  double delta = 1e-3 * (width > 0.0 ? width : std::max(1.0, std::abs(p2)));
  HopfPoint hopf = hopf_at(delta);
  for (int k = 0; k < 3; ++k) {
    const double slope = *hopf.lyapunov / delta;
    if (!(std::abs(slope) > 0.0) || !std::isfinite(slope))
      throw std::runtime_error("generalized Hopf at " + where +
                               ": l1 does not change along the Hopf curve in " +
                               system.parameter_names()[gh.at.second]);
    const double next = std::clamp(l1_wanted / slope, -0.5 * std::abs(width > 0 ? width : delta),
                                   0.5 * std::abs(width > 0 ? width : delta));
    if (k > 0 && std::abs(next - delta) <= 0.1 * std::abs(delta)) break;
    delta = next;
    hopf = hopf_at(delta);
  }
  if (!(*hopf.lyapunov * gh.l2 < 0.0))
    throw std::runtime_error("generalized Hopf at " + where + ": the Hopf point at " +
                             at_values(system, hopf.values, gh.at.first, gh.at.second) +
                             " has l1 = " + format_double(*hopf.lyapunov) + ", of l2's sign (" +
                             format_double(gh.l2) + "): no fold of cycles is born there");

  // 2. Its family, continued in the first parameter until it turns.
  GeneralizedHopfFold out;
  out.hopf = hopf;
  ContinuationOptions family_options = options.family;
  if (!(family_options.lower < family_options.upper)) {
    family_options.lower = options.curve.first_lower;
    family_options.upper = options.curve.first_upper;
  }
  family_options.detect_bifurcations = true;
  HopfStartOptions start = options.start;
  if (start.amplitude == 0.0) start.amplitude = amplitude / 3.0;
  std::atomic<bool> turned{false};
  ContinuationCallbacks watch = family;
  watch.on_event = [&](const Bifurcation& b) {
    if (family.on_event) family.on_event(b);
    if (b.type == BifurcationType::Fold && b.located()) turned = true;
  };
  watch.stop_requested = [&] {
    return turned.load() || (family.stop_requested && family.stop_requested());
  };
  out.family = continue_from_hopf(system, gh.at.first, hopf, family_options, watch, start);
  const auto fold = std::find_if(
      out.family.events.begin(), out.family.events.end(),
      [](const Bifurcation& b) { return b.type == BifurcationType::Fold && b.located(); });
  if (fold == out.family.events.end())
    throw std::runtime_error(
        "generalized Hopf at " + where + ": the family born at the Hopf point " +
        at_values(system, hopf.values, gh.at.first, gh.at.second) +
        " (l1 = " + format_double(*hopf.lyapunov) + ") did not turn: " + out.family.stop_reason);
  out.fold = *fold;

  // 3. The fold's curve in both parameters, ended halfway between its start and GH (in the
  // scaled parameters: the orbits' amplitude there about 0.7 of the start's), where it
  // degenerates.
  CurveOptions curve_options = options.curve;
  const double w1 = curve_options.first_upper - curve_options.first_lower;
  const double w2 = curve_options.second_upper - curve_options.second_lower;
  curve_options.end_first = p1;
  curve_options.end_second = p2;
  curve_options.end_radius =
      0.5 * std::hypot((out.fold.parameter - p1) / w1,
                       (system.parameter(hopf.values, gh.at.second) - p2) / w2);
  curve_options.end_name = "the generalized Hopf point";
  out.curve = continue_curve(system, out.family, out.fold, gh.at.second, curve_options, callbacks);
  out.curve.origin = "LP of the family born near GH at " + where +
                     " (l2 = " + format_number(gh.l2) + "), at " + out.curve.first_name + " = " +
                     format_double(out.fold.parameter) + ", " + out.curve.second_name + " = " +
                     format_double(system.parameter(hopf.values, gh.at.second));
  return out;
}

}  // namespace sympathy
