#pragma once
// Stopping a run cleanly on SIGTERM (a batch system's notice before it kills a job) or SIGINT
// (Ctrl-C): the handler only sets a flag; the run loop reads it after each step, writes a
// checkpoint of that step and ends with status "interrupted" (docs/restart.md). A second SIGINT
// while the first is being handled kills the process as the default action would; a second
// SIGTERM is ignored (a scheduler and mpirun may each send one; the scheduler's SIGKILL follows).
namespace ballista {

/// Installs the handlers while alive (the run loop's steps) and restores the previous ones after:
/// a signal during setup or the end-of-run work acts as it would without Ballista.
class InterruptScope {
 public:
  InterruptScope();
  ~InterruptScope();
  InterruptScope(const InterruptScope&) = delete;
  InterruptScope& operator=(const InterruptScope&) = delete;

 private:
  void (*term_)(int) = nullptr;
  void (*int_)(int) = nullptr;
};
/// True once SIGTERM or SIGINT has arrived, or the caller asked (request_interrupt).
bool interrupt_requested();
/// Stops the run as a signal would (a checkpoint of the step, status "interrupted"): for a caller
/// that runs Ballista in its own process, e.g. the Python module's progress callback.
void request_interrupt();
/// True when the pending request came from request_interrupt, not from a signal.
bool interrupt_from_caller();
/// Forgets an earlier request (a new run starts uninterrupted).
void clear_interrupt();

}  // namespace ballista
