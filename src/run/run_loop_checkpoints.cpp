// The run loop's checkpoints (docs/restart.md): by simulated time, by wall time, on a signal, and
// of the last good step after a failure (replayed from the newest checkpoint: the run is
// deterministic).
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "analysis/penetration_probe.hpp"
#include "io/checkpoint_file.hpp"
#include "run/interrupt.hpp"
#include "run/restart_checks.hpp"
#include "run/run_loop.hpp"

namespace ballista {

RunLoop::Marks RunLoop::marks_now() const {
  return Marks{rs_,
               history_ ? history_->bytes() : 0,
               writer_->count(),
               writer_->xdmf_body_end(),
               penetration_ ? penetration_->samples() : 0,
               tracker_->state(),
               calls_since_checkpoint_.size(),
               tension_};
}

void RunLoop::write_checkpoint(const Marks& m, const char* why) {
  StateArchive a;
  a.put_text("run.deck", sc_.resolved_yaml);
  a.put_text("run.deck_file", restart_ ? restart_->text("run.deck_file") : sc_.file);
  a.put_text("run.solver", solver_->name());
  a.put_text("run.layout", layout_signature(sc_));
  a.put_int("run.step", solver_->steps());  // checked against the file's name when it is read
  solver_->save_state(a);
  RunState saved = m.rs;
  saved.particle_steps = comm_.sum(m.rs.particle_steps);  // each rank counts its own: the total
  saved.wall_before =
      rs_.wall_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  saved.warnings = run_warnings();
  saved.save(a);
  a.put_int("run.history_bytes", m.history_bytes);
  const ParticleWriter::State ws = writer_->state_at(m.outputs, m.xdmf_body_end);
  a.put_int("run.outputs", ws.count);
  a.put_text("run.xdmf", ws.xdmf_body);
  if (penetration_) penetration_->save_state(a, m.penetration_samples);
  m.tension.save(a);
  if (!tracker_->empty() && root_) tracker_->save_state(a, m.tracks);
  const std::string path = checkpoint_path(opt_.out_dir, solver_->steps());
  if (root_) {  // several ranks: rank 0's archive holds every rank's state (Solver::save_state)
    write_checkpoint_file(path, a);
    prune_checkpoints(opt_.out_dir, sc_.output.checkpoint_keep);
  }
  newest_checkpoint_ = path;
  calls_since_checkpoint_.clear();
  wall_of_last_checkpoint_ = std::chrono::steady_clock::now();
  spdlog::info("checkpoint at step {} (t = {:.6g} s, {}): {}", solver_->steps(), solver_->time(), why, path);
}

/// After a step: a checkpoint when the simulated-time or the wall-time interval has passed.
void RunLoop::maybe_checkpoint() {
  if (!checkpointing_ || solver_->time() >= rs_.end * (1.0 - 1e-12)) return;
  const char* why = nullptr;
  if (sc_.output.checkpoint_interval > 0 && solver_->time() >= rs_.next_checkpoint * (1.0 - 1e-12)) {
    while (rs_.next_checkpoint <= solver_->time() * (1.0 + 1e-12))
      rs_.next_checkpoint += sc_.output.checkpoint_interval;
    why = "output.checkpoint_interval";
  }
  const double minutes =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_of_last_checkpoint_).count() / 60.0;
  // Several ranks: rank 0's clock decides for all (the checkpoint is collective).
  bool wall_due = opt_.checkpoint_minutes > 0 && minutes >= opt_.checkpoint_minutes;
  if (opt_.checkpoint_minutes > 0 && comm_.distributed()) comm_.broadcast(&wall_due, sizeof wall_due, 0);
  if (wall_due) why = "--checkpoint-every-minutes";
  if (!why) return;
  // A checkpoint that cannot be written (disk full) does not stop the run: the previous ones stay.
  try {
    write_checkpoint(marks_now(), why);
  } catch (const std::exception& e) {
    spdlog::error("could not write a checkpoint at step {}: {} (the run goes on; the newest checkpoint is {})",
                  solver_->steps(), e.what(), newest_checkpoint_.empty() ? "none" : newest_checkpoint_);
  }
}

/// After a step: the due checkpoint, then a signal's request to stop (run/interrupt.hpp), which
/// checkpoints this step (if not just done) and ends the loop. True: stop.
bool RunLoop::after_step() {
  maybe_checkpoint();
  // Several ranks: a signal reaches the ranks at different steps; they stop together.
  const bool asked = comm_.distributed() ? comm_.any(interrupt_requested()) : interrupt_requested();
  if (!asked || solver_->time() >= rs_.end * (1.0 - 1e-12)) return false;
  if (newest_checkpoint_ != checkpoint_path(opt_.out_dir, solver_->steps()))
    write_checkpoint(marks_now(), interrupt_from_caller() ? "interrupted by the caller" : "interrupted by a signal");
  interrupted_ = true;
  return true;
}

/// The state at the start of the iteration that failed, as a checkpoint to restart from with
/// other settings. A failure leaves a half-updated state (inside a step) or one whose outputs and
/// stage bookkeeping were cut short (the drift guard, a stage that did not settle), so the solver
/// goes back to the newest checkpoint and replays the calls made before that iteration (each step
/// after its stable_dt, as the loop does).
void RunLoop::checkpoint_last_good_step() {
  try {
    if (newest_checkpoint_.empty()) throw Error("no checkpoint to replay from");
    solver_->load_state(read_checkpoint_file(newest_checkpoint_));
    const std::vector<SolverCall> calls(calls_since_checkpoint_.begin(),
                                        calls_since_checkpoint_.begin() + static_cast<std::ptrdiff_t>(good_.calls));
    for (const SolverCall& c : calls) {
      if (c.stage >= 0) {
        solver_->begin_stage(c.stage, c.damping);
      } else {
        (void)solver_->stable_dt();
        solver_->step(c.dt);
      }
    }
    write_checkpoint(good_, "the start of the step that failed");
    result_.checkpoint = newest_checkpoint_;
  } catch (const std::exception& w) {
    spdlog::error("could not write a checkpoint of the last good step: {} (the newest checkpoint is {})", w.what(),
                  newest_checkpoint_.empty() ? "none" : newest_checkpoint_);
    result_.checkpoint = newest_checkpoint_;
  }
}

}  // namespace ballista
