#pragma once
// Checkpoint files (docs/restart.md): a StateArchive as one HDF5 file
// DIR/checkpoints/checkpoint_<step>.h5, written to a temporary name and renamed once complete,
// so a run killed at any moment (SIGKILL included) leaves only complete checkpoints. Layout:
// attribute "format" = "ballista-checkpoint-1" on the root, groups /real (float64 arrays),
// /int (int64 arrays) and /text (uint8 arrays), one dataset per archive key.
#include <string>
#include <utility>
#include <vector>

#include "core/state_archive.hpp"

namespace ballista {

/// Writes `archive` to `path` atomically (temporary file, fsync, rename); throws Error.
void write_checkpoint_file(const std::string& path, const StateArchive& archive);

/// Reads a checkpoint file; throws Error naming the file if it is not a complete checkpoint.
StateArchive read_checkpoint_file(const std::string& path);

/// One text of a checkpoint (e.g. "run.deck") without reading the rest; throws Error.
std::string read_checkpoint_text(const std::string& path, const std::string& key);

/// The newest checkpoint of out_dir whose deck can be read (an unreadable newer one is skipped
/// with a warning), and that deck's text; throws Error if out_dir has none.
std::pair<std::string, std::string> newest_checkpoint(const std::string& out_dir);

/// The checkpoints folder of a results folder: out_dir/checkpoints.
std::string checkpoint_dir(const std::string& out_dir);

/// Path of the checkpoint of `step` in out_dir's checkpoints folder.
std::string checkpoint_path(const std::string& out_dir, long step);

/// The complete checkpoints in out_dir (temporary files ignored), oldest first (by step).
std::vector<std::string> list_checkpoints(const std::string& out_dir);

/// Removes the checkpoints of out_dir written after `path` (by step: a restart from an older
/// one abandons them); returns how many were removed.
int remove_checkpoints_after(const std::string& out_dir, const std::string& path);

/// Removes all but the newest `keep` checkpoints of out_dir; returns how many were removed.
int prune_checkpoints(const std::string& out_dir, int keep);

}  // namespace ballista
