// Accuracy presets of an orbit's shooting flow and a branch's steps, one table for every door (the
// library's defaults, the command line's --accuracy, study and map files, Python): the same call
// gives the same numbers whichever way it came in. Chosen by measurement on the row setup's
// anti-phase k-branch (the numbers are beside apply_accuracy in accuracy.cpp; `sympathy bench`
// section (f) repeats them).
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "sympathy/continuation/continuation_options.hpp"
#include "sympathy/continuation/periodic_orbit.hpp"

namespace sympathy {

// Fast: Dormand-Prince at rtol 1e-8 and coarser branch steps, located points within 4e-7.
// Default: Adams at rtol 5e-12 (BDF where the start measures stiff), located points within 1e-8:
// OrbitOptions' and ContinuationOptions' own defaults. High: the same five times tighter.
enum class Accuracy { Fast, Default, High };

// "fast", "default", "high".
std::string to_string(Accuracy accuracy);
// The preset `name` names, or nothing.
std::optional<Accuracy> accuracy_named(std::string_view name);

// The preset's method, sensitivities and tolerances: the shooting flow's (with the switch to BDF
// where the start measures stiff), and for Fast the transient's too.
void apply_accuracy(Accuracy accuracy, OrbitOptions& options);
// ... and a branch's step control: Fast takes coarser steps where the multipliers move, Default
// and High the library's.
void apply_accuracy(Accuracy accuracy, ContinuationOptions& options);

}  // namespace sympathy
