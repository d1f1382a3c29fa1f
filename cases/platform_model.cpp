#include "sympathy/cases/platform_model.hpp"

#include <stdexcept>

namespace sympathy {

PlatformModel::PlatformModel(const ModelSpec& spec)
    : directions_(spec.directions), metronomes_(static_cast<int>(spec.metronomes.size())) {
  const auto problems = spec.problems();
  if (!problems.empty())
    throw std::invalid_argument("invalid model: " + problems.front().first + " must be " +
                                problems.front().second);
  std::vector<double> raw{spec.M, spec.cx, spec.cy, spec.kx, spec.ky};
  for (const auto& m : spec.metronomes) {
    raw.push_back(m.values.at("mp"));
    raw.push_back(m.values.at("mb"));
  }
  std::vector<NamedParameter> named = platform_parameters(directions_);
  // Shared masses cover the metronomes that do not override them, as in the full model.
  for (int k = 0; k < 2; ++k) {
    const std::string key = k == 0 ? "mp" : "mb";
    NamedParameter shared{key, {}};
    for (int i = 0; i < metronomes_; ++i)
      if (!spec.metronomes[i].overridden.count(key)) shared.raw.push_back(5 + 2 * i + k);
    if (!shared.raw.empty()) named.push_back(shared);
  }
  for (int i = 0; i < metronomes_; ++i) {
    named.push_back({"mp" + std::to_string(i + 1), {5 + 2 * i}});
    named.push_back({"mb" + std::to_string(i + 1), {6 + 2 * i}});
  }
  set_parameter_layout(std::move(named), std::move(raw));
}

std::vector<std::string> PlatformModel::state_names() const {
  if (directions_ == 1) return {"x", "vx"};
  return {"x", "y", "vx", "vy"};
}

double PlatformModel::total_mass(const ParameterValues& raw) const {
  double Mt = raw[0];
  for (int i = 0; i < metronomes_; ++i) Mt += raw[5 + 2 * i] + raw[6 + 2 * i];
  return Mt;
}

}  // namespace sympathy
