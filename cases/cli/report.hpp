// How orbits are shown: text for people, JSON for programs. Shared by the commands.
#pragma once

#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "continuation/periodic_orbit.hpp"
#include "core/ode_system.hpp"

namespace sympathy::cli {

struct OrbitReport {
  std::vector<double> amplitudes;  // half the range of each position over one period
};

// Samples the orbit over one period (plain integration) for its amplitudes.
OrbitReport describe_orbit(const OdeSystem& system, const PeriodicOrbit& orbit);

void print_orbit(std::FILE* out, const OdeSystem& system, const PeriodicOrbit& orbit,
                 const OrbitReport& report, const OrbitOptions& options);

nlohmann::json orbit_json(const OdeSystem& system, const PeriodicOrbit& orbit,
                          const OrbitReport& report);
// [[re, im], ...]
nlohmann::json multipliers_json(const FloquetAnalysis& floquet);
// {name: value} of every parameter of the system
nlohmann::json parameters_json(const OdeSystem& system);

}  // namespace sympathy::cli
