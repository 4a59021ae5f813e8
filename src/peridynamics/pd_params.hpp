#pragma once
// The deck's peridynamics.* parameters: the spec list, and the checks of the section against the
// rest of the deck made before anything is seeded.
#include <string>
#include <vector>

#include "materials/material.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// The spec of every peridynamics.* key, in the order docs/deck.md lists them.
std::vector<ParamSpec> pd_params();

/// A DeckError at a key of the peridynamics section (what the specs cannot check), at its line.
[[noreturn]] void pd_section_error(const Scenario& sc, const std::string& key, const std::string& message);

/// Bond ends per point of a full family (the memory estimate; fewer near a surface).
double full_family_size(const Scenario& sc);

/// The deck's horizon, checked before anything is seeded (a family as large as the body would
/// cost its memory first): at least the lattice spacing, and, when it spans more than ten
/// spacings, at most twice every solid body's largest extent; beyond that every point's family
/// holds the whole body and its bonds cannot localise damage (beyond half of it, a warning: a test
/// body of a few points at m = 3 is legal; the explosive's gas horizon scales with its own
/// lattice). And the bonds' materials: only a solid's elastic moduli, nothing a bond would drop.
/// Returns `sc`.
const Scenario& checked_for_bonds(const Scenario& sc);

}  // namespace ballista
