#pragma once
// penetration.convergence_record: the JSON record of a grid study of this deck
// (validation/convergence_record.py), read when the deck is, so that a missing or malformed
// record is a deck error at its key.
#include "deck/deck_node.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

/// The record `n` names in `convergence_record` (relative to the deck's folder); an empty record
/// when the key is absent. The resolved deck keeps the record's absolute path.
ConvergenceRecord read_convergence_record(DeckNode& n);

}  // namespace ballista
