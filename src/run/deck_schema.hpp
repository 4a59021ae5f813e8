#pragma once
// The JSON Schema of run decks (`ballista schema`): what an editor with a YAML language server
// needs to complete and check a deck. Built from the deck readers themselves, never from a second
// list of keys: the examples are read with a schema recorder active (deck/schema_recorder.hpp),
// which collects every key the readers ask for along the branches those decks take, and the
// registries add every material model's, solver section's and probe kind's parameters.
#include <string>
#include <vector>

namespace ballista {

/// The schema (JSON Schema draft 2020-12, as text) from reading `decks` (run decks; each must be
/// valid) and the registries. Types, ranges, choices, units and defaults of the keys are given;
/// keys the schema does not list are not refused by it (a key no deck reached is not listed, and
/// `ballista run` refuses unknown keys itself, naming the closest valid one).
std::string deck_schema(const std::vector<std::string>& decks);

/// The run decks shipped with Ballista: <data dir>/examples/*.yaml without the drive decks
/// (drive_*.yaml), sorted.
std::vector<std::string> example_run_decks();

}  // namespace ballista
