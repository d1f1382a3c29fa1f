// The journal of a basin walk (basin_walk.hpp): each run's fate as a row of plain fields
// (task_journal.hpp), streamed as the run finishes, and read back when a walk is resumed after a
// kill, so that nothing computed is lost and a resumed walk's results equal an uninterrupted
// one's.
//
// A row keeps what the walk's later steps and files read of a fate: its kind, the attractor's
// index among the value's, when it stopped, a torus' rotation number, an equilibrium's state, a
// new orbit's state and period (to the last bit: %.17g), the note. A new orbit is solved again
// from them when read (basin_walk.cpp): Newton starts at the converged point, so it stops there
// and the orbit and its multipliers come out as the run found them.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sympathy/continuation/attractor_run.hpp"
#include "sympathy/continuation/task_journal.hpp"

namespace sympathy {

// The columns after the task index: value, start, fate, attractor, stopped_at, rotation_number,
// period, state, note.
TaskJournal::Row walk_journal_header();
// Run `start` at value `value` (the walked parameter's) ended with `fate`. A note's commas,
// quotes, line breaks, '%' and the separators 0x1e, 0x1f are written %XX (the journal's fields
// are plain), and read back as they were.
TaskJournal::Row walk_journal_row(double value, std::size_t start, const AttractorFate& fate);
// The fate a row records (a new orbit's `orbit` holds only its state0 and period). Throws
// InputError naming `where` (the journal's file and task) for a row that is not one.
AttractorFate walk_journal_fate(const TaskJournal::Row& row, const std::string& where);

}  // namespace sympathy
