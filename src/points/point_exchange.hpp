#pragma once
// Moving points between ranks: migration to the rank that owns their position, and the
// gather of every rank's points for output. Whole points move, every field with them (ids are
// global and travel too), so nothing but their place in the store changes.
#include <vector>

#include "core/communicator.hpp"
#include "core/field_store.hpp"

namespace ballista {

/// Sends each point p with dest[p] != comm.rank() to that rank (collective). Kept points stay in
/// order; received ones are appended in source-rank order. Returns the number this rank received
/// plus the number it sent (0: its store is unchanged).
Index migrate_points(const Communicator& comm, FieldStore& store, const std::vector<int>& dest);

/// Every rank's points on `root`, in increasing id order (so a file does not depend on the
/// decomposition), or with `by_id` false in rank order, each rank's in its own order (a
/// checkpoint); other ranks get an empty store. Collective.
FieldStore gather_points(const Communicator& comm, const FieldStore& store, int root = 0, bool by_id = true);

/// Every rank's values on `root`, concatenated in rank order (empty elsewhere). Collective.
std::vector<double> gather_values(const Communicator& comm, const std::vector<double>& mine, int root = 0);

}  // namespace ballista
