#include "sympathy/continuation/curve_output.hpp"

#include <cmath>

#include "sympathy/continuation/branch_output.hpp"

namespace sympathy {

namespace {

nlohmann::json complex_list(const std::vector<std::complex<double>>& values) {
  nlohmann::json j = nlohmann::json::array();
  for (const auto& c : values) j.push_back({c.real(), c.imag()});
  return j;
}

// JSON has no NaN: a rotation number that does not apply is null.
nlohmann::json number_or_null(double v) {
  return std::isfinite(v) ? nlohmann::json(v) : nullptr;
}

nlohmann::json point_json(const CurvePoint& p) {
  return {{"index", p.index},
          {"first", p.first},
          {"second", p.second},
          {"period", p.period},
          {"stability", to_string(p.floquet.stability)},
          {"critical", complex_list(p.critical)},
          {"rotation", number_or_null(p.rotation)},
          {"neutral_saddle", p.neutral_saddle},
          {"test", p.test},
          {"residual", p.residual},
          {"trivial_multiplier_error", p.floquet.trivial_error},
          {"uncertainty", number_or_null(p.uncertainty)},
          {"multipliers", multipliers_json(p.floquet)},
          {"state0", as_vector(p.state0)}};
}

}  // namespace

nlohmann::json curve_json(const BifurcationCurve& curve, const OrbitDescriber* describer) {
  const auto layout = describer ? describer->layout() : std::vector<OrbitDescriber::Group>();
  const auto described = [&](const CurvePoint& p) {
    nlohmann::json j = point_json(p);
    add_description(j, layout, p.description);
    return j;
  };
  nlohmann::json j;
  j["kind"] = to_string(curve.kind);
  add_curve_frame(j, curve);
  if (!curve.subspace.empty()) {
    j["subspace"] = curve.subspace;
    j["symmetry"] = to_string(curve.symmetry);  // the critical multipliers: "breaks", "keeps"
  }
  nlohmann::json points = nlohmann::json::array();
  for (const auto& p : curve.points) points.push_back(described(p));
  j["points"] = points;
  nlohmann::json events = nlohmann::json::array();
  for (const auto& e : curve.events)
    events.push_back({{"type", e.type},
                      {"description", e.description},
                      {"first", e.first},
                      {"second", e.second},
                      {"uncertainty", number_or_null(e.uncertainty)},
                      {"located", e.located},
                      {"after_point", e.after_point},
                      {"note", e.note},
                      {"point", described(e.at)}});
  j["events"] = events;
  j["seconds"] = curve.seconds;
  j["monodromies"] = curve.evaluations;
  j["noise"] = curve.noise;  // the integration's, measured at the start
  j["flow"] = {{"integrations", curve.flow.calls}, {"steps", curve.flow.steps}};
  return j;
}

CurveCsvWriter::CurveCsvWriter(const std::string& path, const OdeSystem& system,
                               const std::string& first, const std::string& second,
                               const OrbitDescriber* describer)
    : csv_(path, [&] {
        std::vector<std::string> h{"index",        first,
                                   second,         "period",
                                   "stability",    "unstable_count",
                                   "critical_re",  "critical_im",
                                   "critical2_re", "critical2_im",
                                   "rotation",     "test",
                                   "residual",     "trivial_multiplier_error",
                                   "uncertainty",  "iterations",
                                   "step"};
        if (describer)
          for (const auto& g : describer->layout())
            for (const auto& label : g.labels) h.push_back(g.csv_prefix + label);
        for (int i = 0; i < system.dimension(); ++i) {
          h.push_back("mu" + std::to_string(i + 1) + "_re");
          h.push_back("mu" + std::to_string(i + 1) + "_im");
        }
        for (const auto& n : system.state_names()) h.push_back(n);
        return h;
      }()) {
  if (describer)
    for (const auto& g : describer->layout()) described_ += g.labels.size();
}

void CurveCsvWriter::write(const CurvePoint& p) {
  const auto& f = p.floquet;
  const std::complex<double> c1 = p.critical.empty() ? NAN : p.critical[0];
  const std::complex<double> c2 = p.critical.size() > 1 ? p.critical[1] : NAN;
  std::vector<std::string> row{std::to_string(p.index),      format_double(p.first),
                               format_double(p.second),      format_double(p.period),
                               to_string(f.stability),       std::to_string(f.unstable_count),
                               format_double(c1.real()),     format_double(c1.imag()),
                               format_double(c2.real()),     format_double(c2.imag()),
                               format_double(p.rotation),    format_double(p.test),
                               format_double(p.residual),    format_double(f.trivial_error),
                               format_double(p.uncertainty), std::to_string(p.iterations),
                               format_double(p.step)};
  for (std::size_t k = 0; k < described_; ++k)
    row.push_back(k < p.description.size() ? format_double(p.description[k]) : "");
  for (const auto& m : f.multipliers) {
    row.push_back(format_double(m.value.real()));
    row.push_back(format_double(m.value.imag()));
  }
  for (int i = 0; i < p.state0.size(); ++i) row.push_back(format_double(p.state0[i]));
  csv_.row(row);
}

}  // namespace sympathy
