#pragma once
// One entry of a deck's `materials:` map (docs/deck.md, "materials"), shared by the run decks
// (deck/deck_reader) and the drive decks of the single-element driver (driver/drive_deck).
#include <map>
#include <string>

#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// Reads parameter `p` from `key` of the map `n` into `out` (a choice, an integer or a number;
/// required, optional or defaulted as the spec says, the default recorded in the resolved deck),
/// and its mark into `marks` if the key is given. Shared by materials and solver sections.
void read_param(DeckNode& n, const std::string& key, const ParamSpec& p, ParamValues& out,
                std::map<std::string, DeckMark>& marks);

/// Reads the material `name` of the `materials:` map `materials`: its registered model, every
/// parameter of the model (defaults filled; "group.key" parameters from the sub-map `group:`),
/// and the model's own cross-checks (Model::make). Every problem is a DeckError at the offending
/// key (file, line, column, key path).
MaterialSpec read_material_spec(DeckNode& materials, const std::string& name);

}  // namespace ballista
