#pragma once
// Full histories of chosen particles (deck key output.track.ids; thesis seed 000 §4.2.1-4.2.2:
// particle histories extracted from a simulation and replayed through the single-element driver).
//
// For every tracked particle id, DIR/tracks/ receives
//   particle_<id>.csv          its F-table: `t,F11,...,F33` (driver/ftable_csv format), one row per
//                              solver step, the first row the state before the first step (t = 0,
//                              the seeded F, normally I), numbers in shortest round-trip form (the
//                              exact doubles); `ballista drive` replays it with
//                              `drive: {table: tracks/particle_<id>.csv, substeps: 1}`;
//   particle_<id>_history.csv  the in-solver state after each step, in the columns of the driver's
//                              history.csv where they exist (step, t, F, sigma_*, sigma_bar_*, I1,
//                              sqrt_J2, pressure, the model's state fields, plastic_work_total and
//                              internal_energy per m^3 of reference volume), for comparison.
// If the run stops with a PhysicsError, the F-table gets one more row: the F of the failing step
// (so that the replay reproduces the failure: an inverted F is rejected by the drive deck reader,
// a non-finite stress is reproduced by the model); the history file ends at the last completed
// step. A particle of a body activated later starts its files at its activation, with the F it
// was seeded with; a deleted particle's files end when it leaves.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/state_archive.hpp"
#include "io/history_writer.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

class ParticleTracker {
 public:
  /// ids: the particles to track (output.track.ids); total_ids: how many particles the run
  /// seeded (ids are 0 .. total_ids - 1), to reject unknown ids with a DeckError at
  /// output.track.ids. Creates DIR/tracks if there is anything to track.
  ParticleTracker(const Scenario& sc, const std::string& out_dir, std::int64_t total_ids);

  bool empty() const { return ids_.empty(); }
  /// Records every tracked particle present in `points` at time t after `step` steps
  /// (call with the initial state before the first step, then after every step).
  void record(const FieldStore& points, double t, long step);
  /// After a PhysicsError: appends the current F of every tracked particle to its F-table only.
  void record_failure(const FieldStore& points, double t);

  /// Checkpoint: for each open track its id, material, whether it started, and the lengths of
  /// its two files; and the time of the last record (docs/restart.md).
  struct State {
    std::vector<std::int64_t> tracks;  ///< 5 per open track: id, material, started, table bytes, history bytes
    double t_prev = 0.0;
  };
  State state() const;
  void save_state(StateArchive& archive, const State& s) const;
  /// Restart: the tracks reopened and cut back to their lengths at the checkpoint.
  void load_state(const StateArchive& archive);

 private:
  struct Track {
    std::unique_ptr<HistoryWriter> table, history;
    std::vector<bool> keep;  ///< which of the driver's history columns the solver has
    bool started = false;
    int material = 0;
  };
  /// index of each tracked id in `points` (-1 if absent).
  void locate(const FieldStore& points);
  /// Opens the two files of a track (resume_bytes: continue them, cut back to these lengths).
  void open(std::int64_t id, int material, const long long* resume_bytes = nullptr);

  std::string dir_;
  std::vector<std::int64_t> ids_;
  std::vector<Index> where_;
  std::map<std::int64_t, Track> tracks_;
  std::vector<std::vector<std::string>> state_names_;  ///< per material index
  double t_prev_ = 0.0;                                ///< time of the previous record (start of the current step)
};

}  // namespace ballista
