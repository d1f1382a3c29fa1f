// How orbits are shown: text for people, JSON for programs. Shared by the commands.
#pragma once

#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy::cli {

struct OrbitReport {
  std::vector<double> amplitudes;         // half the range of each position over one period
  std::vector<double> phase_differences;  // of each angle but the first, to th1: rad in (-pi, pi]
};

// Samples the orbit over one period (plain integration) for its amplitudes and the phase
// differences of the pendula (from upward zero crossings; NaN for a pendulum that does not
// cross zero).
OrbitReport describe_orbit(const MetronomeModel& model, const PeriodicOrbit& orbit);

void print_orbit(std::FILE* out, const MetronomeModel& model, const PeriodicOrbit& orbit,
                 const OrbitReport& report, const OrbitOptions& options);

// The full report of a flow's work (--verbose).
void print_flow_statistics(std::FILE* out, const FlowStatistics& s);

nlohmann::json orbit_json(const MetronomeModel& model, const PeriodicOrbit& orbit,
                          const OrbitReport& report);
// [[re, im], ...]
nlohmann::json multipliers_json(const FloquetAnalysis& floquet);
// {name: value} of every parameter of the system
nlohmann::json parameters_json(const OdeSystem& system);

}  // namespace sympathy::cli
