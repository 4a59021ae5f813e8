#pragma once
// The run loop of `ballista run` as one object: the solver, its writers, probes, tracker and the
// loop's own state are members; setup, the step loop and stages (run_loop.cpp), history rows
// (run_loop_history.cpp), checkpoints and the replay of a failing step (run_loop_checkpoints.cpp)
// and summary.json (run_loop_summary.cpp) are its methods. Every rank runs it; rank 0 alone
// writes files (docs/parallel.md).
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "core/communicator.hpp"
#include "core/solver.hpp"
#include "core/state_archive.hpp"
#include "io/history_writer.hpp"
#include "io/particle_writer.hpp"
#include "io/run_folder.hpp"
#include "points/probe_registry.hpp"
#include "run/deletion_report.hpp"
#include "run/particle_tracker.hpp"
#include "run/progress.hpp"
#include "run/run_state.hpp"
#include "run/simulation.hpp"
#include "run/stage_criterion.hpp"
#include "run/tension_watch.hpp"

namespace ballista {

class PenetrationProbe;

class RunLoop {
 public:
  /// Takes the results folder, reads and checks a restart, builds the solver, writers, probes
  /// and tracker, and sets the loop's clocks (a new run or the checkpoint's).
  RunLoop(const Scenario& sc, const RunOptions& opt);
  ~RunLoop();
  /// Runs to the end (or a failure or a signal) and writes summary.json.
  RunResult run();

 private:
  /// What the outputs looked like at a state: the loop state and how far history.csv, the
  /// particle files and the penetration series had got.
  struct Marks {
    RunState rs;
    long long history_bytes = 0;
    int outputs = 0;
    std::size_t xdmf_body_end = 0;
    std::size_t penetration_samples = 0;
    ParticleTracker::State tracks;
    std::size_t calls = 0;  ///< solver calls since the newest checkpoint at the mark
    TensionWatch tension;
  };
  /// A solver call since the newest checkpoint, so that a failing step can be replayed up to the
  /// step before it (the run is deterministic): a step (stage < 0) or a stage start.
  struct SolverCall {
    double dt;
    int stage;
    double damping;
  };

  // run_loop.cpp: setup, the steps and the stages.
  void open_history();
  void start_clocks();
  void start_run();
  void step_loop();
  void start_progress();
  std::vector<std::string> run_warnings() const;
  std::map<std::string, std::string> probe_units() const;
  double next_dt();
  void after_preparation_step(double dt);
  void check_equilibrium_stage(const StageSpec& st, double elapsed);
  void begin_stage(int stage, double damping);
  void next_stage(const std::string& how, const EquilibriumCheck* check);
  void write_output();
  void on_physics_failure(const PhysicsError& err);

  // run_loop_history.cpp: history rows, probes, tracks.
  /// The scale of the energy residual: kinetic + |internal| + |work of the loads and of damping|;
  /// explosives add the chemical energy released so far (the energy their products work with).
  static double energy_scale_of(const EnergyTotals& e);
  std::vector<double> probe_values(const EnergyTotals& e) const;
  double drift_of(const EnergyTotals& e);
  double history_row(double dt);
  void record_history(double step_dt);
  void record_tracks(bool failure);

  // run_loop_checkpoints.cpp.
  Marks marks_now() const;
  void write_checkpoint(const Marks& m, const char* why);
  void maybe_checkpoint();
  bool after_step();
  void checkpoint_last_good_step();

  // run_loop_summary.cpp.
  void write_summary(double wall);

  const Scenario& sc_;
  const RunOptions& opt_;
  const Communicator comm_;
  const bool root_;
  const int nstages_;  ///< preparation stages; the main stage has this index
  std::optional<RunFolder> folder_;
  std::optional<StateArchive> restart_;
  std::unique_ptr<Solver> solver_;
  std::vector<std::unique_ptr<Probe>> probes_;
  std::optional<ParticleWriter> writer_;
  std::vector<std::string> columns_;
  std::vector<bool> nan_allowed_;  ///< columns where nan means "not applicable yet"
  std::unique_ptr<PenetrationProbe> penetration_;
  std::unique_ptr<HistoryWriter> history_;  ///< rank 0's
  std::int64_t seeded_ = 0;                 ///< particle ids run 0 .. seeded - 1 over every body
  std::size_t warning_mark_ = 0;            ///< warnings logged before this run (core/warning_log.hpp)
  std::optional<ParticleTracker> tracker_;
  TensionWatch tension_;  ///< points beyond their material's cohesive limit (run/tension_watch.hpp)
  std::set<std::int64_t> tracked_ids_;
  RunState rs_;
  double interval_ = 0.0;  ///< s, between particle outputs
  bool checkpointing_ = false;
  std::optional<DeletionReport> deletions_;
  std::string nonfinite_column_;  ///< set by history_row
  std::vector<SolverCall> calls_since_checkpoint_;
  std::string newest_checkpoint_;
  std::chrono::steady_clock::time_point wall_start_, wall_of_last_checkpoint_;
  std::unique_ptr<Progress> progress_;
  Marks good_;  ///< the state at the start of the iteration being taken (a failure's last good state)
  bool interrupted_ = false;
  bool physics_failure_ = false;
  RunResult result_;
};

}  // namespace ballista
