#pragma once
// A deck key naming a body (loads, probes, cracks, contact pairs): checked against the bodies read
// so far, with the closest name suggested for a typo.
#include <string>

#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// `key` of `node` as the name of a body of `sc`; "" when absent and not required (every body).
std::string read_body_ref(DeckNode& node, const Scenario& sc, bool required, const std::string& key = "body");

}  // namespace ballista
