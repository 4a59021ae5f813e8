#pragma once
// The run loop's own state (stage, output and checkpoint clocks, energy reference and worst
// drift, the step limiter, the stage log), kept in one struct so that a checkpoint can save it
// and a restart continue it (docs/restart.md).
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "core/solver.hpp"
#include "core/state_archive.hpp"
#include "io/summary_writer.hpp"
#include "run/step_tally.hpp"

namespace ballista {

/// How a preparation stage ended (summary.json "stages").
struct StageRecord {
  std::string name, ended_by;
  double start_time = 0.0, end_time = 0.0, damping = 0.0;
  bool checked = false;  ///< ended by (or after checking) a stress-equilibrium criterion
  double worst_deviation = 0.0, fraction_within = 0.0;
  std::int64_t worst_particle = -1;
  JsonValue json() const;
};

struct RunState {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  int stage = 0;               ///< current stage; the number of preparation stages = main stage
  double stage_start = 0.0;    ///< s, start of the current stage
  double end = kInf;           ///< s, end of the run (known once the main stage starts)
  double next_output = kInf;   ///< s, next particle output
  double next_checkpoint = kInf;  ///< s, next checkpoint by output.checkpoint_interval
  double total0 = 0.0;         ///< J, the energy balance at t = 0
  double energy_scale = 0.0;   ///< J, largest energy scale seen (residual reference)
  double worst_drift = 0.0;
  double min_dt = kInf;        ///< s, smallest stable step seen
  StepLimiter limiter;         ///< the point that set the smallest stable step (to within 10 %)
  double limiter_dt = kInf, limiter_time = 0.0;
  StepTally step_tally;        ///< which points set the step, sampled over the run
  double particle_steps = 0.0;
  double dt = 0.0;             ///< s, the last step taken
  double wall_before = 0.0;    ///< wall seconds of the run's earlier segments (before restarts)
  std::vector<StageRecord> stages;
  std::vector<std::string> warnings;  ///< the run's warnings up to its checkpoint (one line each)

  void save(StateArchive& archive) const;
  void load(const StateArchive& archive);
};

}  // namespace ballista
