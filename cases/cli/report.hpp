// How orbits and events are shown to people (the JSON for programs is the application layer's).
// Shared by the commands.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "cases/app/branch_run.hpp"
#include "cases/app/orbit_run.hpp"
#include "cases/app/study_run.hpp"

namespace sympathy::cli {

// An orbit of any system: `amplitudes` per state from the first (a metronome model gives its
// positions'), `phase_differences` of th2, th3, ... to th1 (empty for other systems), `rms` per
// state (empty: not printed).
void print_orbit(std::FILE* out, const OdeSystem& model, const PeriodicOrbit& orbit,
                 const std::vector<double>& amplitudes,
                 const std::vector<double>& phase_differences, const OrbitOptions& options,
                 const std::vector<double>& rms = {});

// The full report of a flow's work (--verbose).
void print_flow_statistics(std::FILE* out, const FlowStatistics& s);

// Newton's steps and the flow's work (orbit --verbose).
void print_newton_and_flow(std::FILE* out, const PeriodicOrbit& orbit);

// A branch's events as a table: type (with ? where not trusted), parameter, uncertainty, period,
// crossing multiplier, note.
void print_events(std::FILE* out, const Branch& branch);

// A branch of equilibria's events as a table (equilibria, study): type (with ? where not
// located), parameter, uncertainty, the eigenvalue nearest the imaginary axis, note (a Hopf
// point's omega, period and criticality).
void print_equilibrium_events(std::FILE* out, const EquilibriumBranch& branch);

// A walk of basin shares along `parameter` (a study's [basins]): per value the attractors with a
// share (each with its 95% interval) and how the runs ended; then where each share appears or
// disappears, with the events `branches` and `equilibria` located there.
void print_basins_walk(std::FILE* out, const BasinWalk& walk, const std::string& parameter,
                       const std::vector<NamedBranch>& branches,
                       const std::vector<NamedEquilibria>& equilibria);

}  // namespace sympathy::cli
