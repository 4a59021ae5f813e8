#pragma once
// The YAML input deck: reading, validation and resolution into a Scenario (docs/deck.md).
#include <string>
#include <vector>

#include "scenario/scenario.hpp"

namespace ballista {

/// Reads, validates and resolves a deck file. overrides are "key.path=value" strings from the CLI
/// (--set), applied to the YAML tree before validation; list elements are addressed by index
/// (bodies.0.velocity=[0,-100,0]) and map entries by key (materials.copper.yield_stress=3e8).
/// Every problem is reported as a DeckError (file, 1-based line and column, key path, message).
Scenario read_deck(const std::string& path, const std::vector<std::string>& overrides = {});

/// Same from text (file name used in messages).
Scenario parse_deck(const std::string& yaml_text, const std::string& file_name,
                    const std::vector<std::string>& overrides = {});

/// Deck spellings of the enumerations ("3d", "plane_strain", "axisymmetric"; "free", "fixed", ...).
const char* dimension_name(Dimension d);
const char* face_bc_name(FaceBC bc);
/// "x", "y" or "z".
const char* axis_name(int axis);
/// 0, 1 or 2 for "x", "y" or "z" (a name already checked against the axes).
int axis_from(const std::string& name);

}  // namespace ballista
