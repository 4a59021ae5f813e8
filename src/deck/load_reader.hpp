#pragma once
// The deck's `loads`: each entry read by its registered kind (points/load_registry.hpp) through a
// LoadEntry over the entry's node, so that the deck reader names no load kind.
#include <map>
#include <string>

#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Reads `loads` (optional) into sc.loads, in deck order (an entry may stand for several loads);
/// the stress a load should hold its body at in equilibrium goes to `equilibrium_stress` by body
/// name. Needs sc.simulation and sc.bodies read.
void read_loads(DeckNode& root, Scenario& sc, std::map<std::string, Vec3>& equilibrium_stress);

/// `curve` of a load: [time, scale] pairs with strictly increasing times (none: scale 1).
LoadCurve read_load_curve(DeckNode& entry);

}  // namespace ballista
