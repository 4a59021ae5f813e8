#include "run/progress.hpp"

#include <unistd.h>

#include <cstdio>

#include <spdlog/spdlog.h>

namespace ballista {

Progress::Progress(double end_time, bool enabled)
    : end_time_(end_time), enabled_(enabled), tty_(isatty(fileno(stderr)) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(double time, long step, double dt) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double frac = end_time_ > 0 ? std::min(1.0, time / end_time_) : 1.0;
  const double eta = frac > 0 ? wall * (1.0 - frac) / frac : 0.0;
  if (tty_) {
    if (std::chrono::duration<double>(now - last_).count() < 0.2 && frac < 1.0) return;
    last_ = now;
    const int width = 30;
    const int filled = static_cast<int>(frac * width);
    std::string bar(filled, '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r[%s] %5.1f%%  t = %.4e s  step %ld  dt = %.3e s  ETA %.0f s   ",
                 bar.c_str(), 100.0 * frac, time, step, dt, eta);
    std::fflush(stderr);
    return;
  }
  const int decile = static_cast<int>(frac * 10.0);
  if (decile > last_decile_ || std::chrono::duration<double>(now - last_).count() > 30.0) {
    last_decile_ = decile;
    last_ = now;
    spdlog::info("t = {:.4e} s ({:.0f}%), step {}, dt = {:.3e} s, wall {:.1f} s, ETA {:.0f} s", time,
                 100.0 * frac, step, dt, wall, eta);
  }
}

void Progress::finish() {
  if (enabled_ && tty_) std::fprintf(stderr, "\n");
}

}  // namespace ballista
