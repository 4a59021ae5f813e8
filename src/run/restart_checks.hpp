#pragma once
// What a restart may not change (docs/restart.md): the checkpoint's deck against the deck it
// continues with.
#include <string>

#include "core/state_archive.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// The solver, the grid, the bodies' materials and seeding and the materials' models, as text:
/// written into every checkpoint and compared on restart.
std::string layout_signature(const Scenario& sc);

/// Refuses a restart whose deck seeds other points than the checkpoint's (naming the first
/// differing line).
void check_layout(const StateArchive& a, const Scenario& sc, const std::string& path);

/// Refuses a restart whose deck (the checkpoint's, with the --set overrides) changes more than the
/// run's end, outputs, checkpoints, limits and guards, naming what it changes.
void check_restart_changes(const StateArchive& a, const Scenario& sc, const std::string& path);

}  // namespace ballista
