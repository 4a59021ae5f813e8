#pragma once
// Progress reporting: a one-line bar on a terminal, plain periodic log lines otherwise. One
// Progress per phase of a run (each preparation stage, then the main stage), so that the fraction
// and the ETA are of the phase running, not of a simulated time that began in an earlier one.
#include <chrono>
#include <functional>
#include <string>

namespace ballista {

/// Where a phase stands after a step, for a caller that follows the run (the Python module's
/// progress callback). SI units.
struct ProgressReport {
  std::string phase;        ///< "" for the main stage, "stage '<name>'" for a preparation stage
  double time = 0.0;        ///< simulated time, s
  double start = 0.0;       ///< the phase's start, s
  double end = 0.0;         ///< the phase's end (its latest end when `bounded`), s
  double fraction = 0.0;    ///< (time - start) / (end - start), in [0, 1]
  long step = 0;            ///< solver steps so far
  double dt = 0.0;          ///< the step just taken, s
  double eta_seconds = 0.0; ///< wall seconds to the phase's end (Progress::eta); NaN before it is known
  bool bounded = false;     ///< the phase ends by a criterion: eta_seconds is an upper bound
};

class Progress {
 public:
  /// A phase from simulated time `start` to `end`. `label` names it in the lines ("stage
  /// 'overburden'"; empty for the main stage). `bounded`: `end` is only the latest the phase can
  /// end (a stage that ends by a criterion), so the ETA is an upper bound and says so.
  Progress(std::string label, double start, double end, bool bounded, bool enabled);
  /// Called every step; prints at most a few times per second (terminal) or every 10 % / 30 s.
  void update(double time, long step, double dt);
  /// Ends the bar line.
  void finish();
  /// Also hands every step's report to `observer` (whether or not the bar is shown).
  void observe(std::function<void(const ProgressReport&)> observer) { observer_ = std::move(observer); }

  /// Seconds to the phase's end: the steps left at the current step, (end - time) / dt, times the
  /// recent wall time per step. The current step rather than the phase's mean, because the step
  /// only shrinks as an impact develops; the recent cost per step rather than the mean, because
  /// the cost grows as points are inserted or the contact spreads.
  static double eta(double time, double end, double dt, double wall_per_step);

 private:
  /// Wall seconds per step over the last sampling window (~1 s), falling back on the phase's mean.
  double wall_per_step(std::chrono::steady_clock::time_point now, long step);

  std::string label_;
  double start_time_, end_time_;
  bool bounded_, enabled_, tty_;
  std::chrono::steady_clock::time_point start_, last_print_, sample_at_;
  long first_step_ = -1, sample_step_ = -1;
  double recent_wall_per_step_ = 0.0;
  int last_decile_ = -1;
  std::function<void(const ProgressReport&)> observer_;
};

}  // namespace ballista
