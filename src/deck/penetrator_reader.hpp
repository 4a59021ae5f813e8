#pragma once
// Rod and discrete-jet bodies of a deck (`rod:` / `jet:` instead of `shape:`; docs/deck.md):
// they expand into cylindrical segments, each with its own velocity and activation time
// (thesis seed 000 §5.1, Fig. 5.2; §6.4 segmented rods).
#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Reads `rod:` (a solid rod, or a segmented one with segment_ld > 0) into body.penetrator,
/// body.segments and body.shape (the first segment).
void read_rod(DeckNode& rod, Dimension dim, const GridSpec& grid, BodySpec& body);

/// Reads `jet:`: a table of segments [radius, length, velocity, insert_time] (inline `segments`
/// or a CSV `file` relative to the deck), inserted in front of the struck face at their times.
void read_jet(DeckNode& jet, Dimension dim, const GridSpec& grid, BodySpec& body);

}  // namespace ballista
