#pragma once
// The run loop of `ballista run`: deck -> solver -> outputs, histories, probes and summary.
#include <cstdint>
#include <functional>
#include <memory>

#include "core/communicator.hpp"
#include <string>
#include <vector>

#include "core/solver.hpp"
#include "run/progress.hpp"
#include "scenario/scenario.hpp"

namespace ballista {

struct RunOptions {
  std::string out_dir = "out";  ///< results folder (created)
  int threads = 0;              ///< OpenMP threads; 0 = the deck's or the default
  bool progress = true;         ///< progress bar on a terminal, periodic log lines otherwise
  bool plots = false;           ///< draw the figures of a fragments table (the CLI: unless --no-plots)
  std::string restart_from;     ///< checkpoint file to continue (its results folder is out_dir); "" = a new run
  double checkpoint_minutes = 0.0;  ///< > 0: also a checkpoint after this many wall minutes (docs/restart.md)
  /// A new run into a folder that is not empty and holds no Ballista run (io/run_folder.hpp).
  bool overwrite = false;
  /// The caller holds out_dir as a RunFolder (the CLI, so that its figures and a re-run are
  /// inside the lock) and has cleared it for a new run; otherwise the run takes the folder.
  bool folder_held = false;
  /// Called on rank 0 after every step with the phase's progress (run/progress.hpp); it may call
  /// request_interrupt (run/interrupt.hpp) to stop the run with a checkpoint, as a signal would.
  std::function<void(const ProgressReport&)> on_progress;
};

/// What a finished (or stopped) run reports.
struct RunResult {
  bool ok = true;
  std::string error;            ///< PhysicsError message when !ok
  std::int64_t failed_particle = -1;  ///< id of the particle the error is about (-1: none)
  long failed_step = 0;         ///< step number of the failure (when !ok)
  long steps = 0;
  double time = 0.0;            ///< simulated time reached, s
  double wall_seconds = 0.0;
  double particle_steps_per_second = 0.0;
  std::vector<std::pair<std::string, double>> probes;  ///< final probe values
  std::vector<std::string> headlines;  ///< depth, holes, fragments (run/headlines.hpp; rank 0)
  std::string checkpoint;       ///< after a failure with checkpoints on, or an interruption: where to restart
  bool interrupted = false;     ///< stopped by SIGTERM/SIGINT after checkpointing (ok is false)
};

/// Builds the materials of the scenario from the registry.
std::vector<std::unique_ptr<Material>> make_materials(const Scenario& sc);

struct SolverFactory;

/// Several ranks: refuses a solver that is not registered as distributed, with an error saying so.
void check_distributed(const Scenario& sc, const SolverFactory& f, const Communicator& comm);

/// Builds the solver named in the scenario (simulation.solver) on `comm` (several ranks only for a
/// solver registered as distributed; the others are refused with an error saying so).
std::unique_ptr<Solver> make_solver(const Scenario& sc, const Communicator& comm = {});

/// Runs the scenario to its end time (run/run_loop.hpp), writing resolved.yaml, particles_*.h5 +
/// particles.xdmf, history.csv, summary.json and (output.track.ids) tracks/particle_<id>*.csv to
/// options.out_dir. A PhysicsError stops the run after the state is written to a new output file
/// (earlier outputs stay intact) and is reported in the result and summary.json (status "failed").
RunResult run_simulation(const Scenario& sc, const RunOptions& options);

}  // namespace ballista
