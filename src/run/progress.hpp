#pragma once
// Progress reporting: a one-line bar on a terminal, plain periodic log lines otherwise.
#include <chrono>
#include <string>

namespace ballista {

class Progress {
 public:
  Progress(double end_time, bool enabled);
  /// Called every step; prints at most a few times per second (terminal) or every 10 % / 30 s.
  void update(double time, long step, double dt);
  /// Ends the bar line.
  void finish();

 private:
  double end_time_;
  bool enabled_;
  bool tty_;
  std::chrono::steady_clock::time_point start_, last_;
  int last_decile_ = -1;
};

}  // namespace ballista
