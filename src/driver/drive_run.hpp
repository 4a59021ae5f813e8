#pragma once
// `ballista drive`: a drive deck -> drive_point -> DIR/history.csv, summary.json, resolved.yaml.
#include <string>

#include "driver/drive_deck.hpp"

namespace ballista {

struct DriveRunResult {
  bool ok = true;
  std::string error;  ///< PhysicsError message when !ok (history.csv ends at the failing step)
  long steps = 0;
  size_t records = 0;
  double wall_seconds = 0.0;
  DriveRecord last;  ///< last record
};

/// Drives the deck's material through its program and writes, in out_dir (created):
/// resolved.yaml (the deck with every default), history.csv (drive_history_columns, one row per
/// record, shortest round-trip numbers) and summary.json (status, material, program, statistics,
/// final state). A PhysicsError is reported in the result and the summary (status "failed");
/// bad programs throw (Error / DeckError).
DriveRunResult run_drive(const DriveDeck& deck, const std::string& out_dir);

/// The error of a history whose stresses are finite but whose invariants are not (moduli near
/// 1e308), naming the first such step; "" if there is none.
std::string drive_invariants_error(const DriveResult& r);

/// The deck's material driven through its program in memory (what run_drive writes, and what the
/// Python module returns): drive_point, then drive_invariants_error. The error that stopped it goes
/// to `error` ("" when it completed), the records up to it stay in the result.
DriveResult drive_deck_point(const DriveDeck& deck, std::string& error);

}  // namespace ballista
