#pragma once
// Bodies may touch but not share space. Two bodies seeded into the same region put two sets of
// points (two masses) where there is one solid: MPM adds their masses on the grid (a plate
// driven at a fifth of its Gurney velocity), coincident peridynamic points exert no force on each
// other, and an explosive fill seeded into its case collapses the first step. The deck is
// refused instead, naming both bodies and the shared volume.
#include "core/field_store.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Throws a DeckError at the later body of the pair if any point of one body lies inside another
/// body (its shape or, for rods and jets, a segment's shape, less its cutouts) by more than 1 %
/// of its own lattice spacing: a point on a shared face is touching, not overlapping. `points`
/// holds every body's seeded points (fields x0, body, volume0).
void check_body_overlaps(const Scenario& sc, const FieldStore& points);

}  // namespace ballista
