#pragma once
// Lighting times of the explosive points of a run: the deck's `detonation` section fed
// to the program burn (points/program_burn.hpp) over the seeded points, written into the
// `lighting_time` state field of the `explosive` material (materials/explosive.cpp).
#include "core/field_store.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Fills `lighting_time` and `burn_time` (detonation.burn_cells spacings / D) of every point whose
/// material is an `explosive` (reference positions x0, lattice spacing cell_size /
/// particles_per_cell of its body). Deck errors: explosives with different detonation speeds or
/// lattice spacings, explosive bodies with a later activation, a detonator away from the charge,
/// explosive that no front reaches. Returns the points lit.
Index light_explosives(const Scenario& sc, FieldStore& points, int particles_per_cell_override);

}  // namespace ballista
