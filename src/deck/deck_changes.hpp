#pragma once
// What a restart may change. A checkpoint stores the resolved deck of its run; `--restart DIR
// --set key=value` resolves that deck again with the overrides. The two resolved texts are
// compared key by key, and only the run's end, outputs, checkpoints, limits and guards may
// differ (docs/restart.md): anything else would continue the run with other physics.
#include <string>
#include <vector>

namespace ballista {

/// One key whose value differs between two resolved decks ("" for a key one of them lacks).
struct DeckChange {
  std::string key_path;
  std::string before, after;
  bool before_absent = false;  ///< the key is not in the first deck at all (not merely null, `key: ~`)
};

/// The leaves (scalars, and lists or maps given or removed as a whole) that differ between two
/// YAML texts, in key-path order; list elements by index. Throws Error if either does not parse.
std::vector<DeckChange> deck_changes(const std::string& before_yaml, const std::string& after_yaml);

/// True if a restart may change this key: simulation.end_time, max_steps, step_limit,
/// energy_drift_limit and threads, every output.* key, and penetration.layers (the holes the
/// analysis measures).
bool restart_may_change(const std::string& key_path);

/// The changes a restart is refused for. `stored` is the checkpoint's resolved deck, `continued`
/// the same deck resolved again by this build with the --set overrides, `plain` resolved again
/// without them. Every change restart_may_change refuses counts, except a key `stored` lacks (absent,
/// not null) that `continued` holds at its `plain` value: a key this build added after the
/// checkpoint was written, at its default. A new key's default is the behaviour from before the key
/// existed (results stay bitwise) for every key but those whose default changed what a run does
/// (mpm.distortion_limit: points older builds left alone are remapped); those are refused.
std::vector<DeckChange> refused_restart_changes(const std::string& stored, const std::string& plain,
                                                const std::string& continued);

}  // namespace ballista
