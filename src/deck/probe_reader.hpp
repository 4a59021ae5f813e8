#pragma once
// The deck's `probes`: each entry read as its registered kind declares its parameters
// (points/probe_registry.hpp), so that the deck reader names no probe kind.
#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Reads `probes` (optional) into sc.probes, in deck order; names are unique. Needs
/// sc.simulation and sc.bodies read.
void read_probes(DeckNode& root, Scenario& sc);

}  // namespace ballista
