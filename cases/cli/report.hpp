// How orbits are shown to people (the JSON for programs is the engine's: branch_output.hpp).
// Shared by the commands.
#pragma once

#include <cstdio>
#include <vector>

#include <nlohmann/json.hpp>

#include "sympathy/cases/metronome_describer.hpp"
#include "sympathy/cases/metronome_model.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"
#include "sympathy/core/ode_system.hpp"

namespace sympathy::cli {

void print_orbit(std::FILE* out, const MetronomeModel& model, const PeriodicOrbit& orbit,
                 const MetronomeDescriber::Report& report, const OrbitOptions& options);

// The full report of a flow's work (--verbose).
void print_flow_statistics(std::FILE* out, const FlowStatistics& s);

}  // namespace sympathy::cli
