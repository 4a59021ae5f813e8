#include "run/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

namespace ballista {

namespace {

/// "42 s", "12 min", "3.4 h".
std::string duration_text(double s) {
  if (!std::isfinite(s)) return "?";
  if (s < 120.0) return fmt::format("{:.0f} s", s);
  if (s < 7200.0) return fmt::format("{:.0f} min", s / 60.0);
  return fmt::format("{:.1f} h", s / 3600.0);
}

}  // namespace

Progress::Progress(std::string label, double start, double end, bool bounded, bool enabled)
    : label_(std::move(label)), start_time_(start), end_time_(end), bounded_(bounded), enabled_(enabled),
      tty_(isatty(fileno(stderr)) != 0), start_(std::chrono::steady_clock::now()), last_print_(start_),
      sample_at_(start_) {}

double Progress::eta(double time, double end, double dt, double wall_per_step) {
  if (!(dt > 0.0) || !(wall_per_step >= 0.0)) return NAN;
  return std::max(0.0, end - time) / dt * wall_per_step;
}

double Progress::wall_per_step(std::chrono::steady_clock::time_point now, long step) {
  if (first_step_ < 0) first_step_ = sample_step_ = step;
  const double window = std::chrono::duration<double>(now - sample_at_).count();
  if (window >= 1.0 && step > sample_step_) {
    recent_wall_per_step_ = window / static_cast<double>(step - sample_step_);
    sample_at_ = now;
    sample_step_ = step;
  }
  if (recent_wall_per_step_ > 0.0) return recent_wall_per_step_;
  const double wall = std::chrono::duration<double>(now - start_).count();
  return step > first_step_ ? wall / static_cast<double>(step - first_step_) : NAN;
}

void Progress::update(double time, long step, double dt) {
  if (!enabled_ && !observer_) return;
  const auto now = std::chrono::steady_clock::now();
  const double per_step = wall_per_step(now, step);
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double span = end_time_ - start_time_;
  const double frac = span > 0 ? std::clamp((time - start_time_) / span, 0.0, 1.0) : 1.0;
  if (observer_)
    observer_(ProgressReport{label_, time, start_time_, end_time_, frac, step, dt,
                             eta(time, end_time_, dt, per_step), bounded_});
  if (!enabled_) return;
  const std::string eta_text = (bounded_ ? "at most " : "") + duration_text(eta(time, end_time_, dt, per_step));
  const std::string label = label_.empty() ? "" : label_ + ": ";
  if (tty_) {
    if (std::chrono::duration<double>(now - last_print_).count() < 0.2 && frac < 1.0) return;
    last_print_ = now;
    const int width = 30;
    std::string bar(static_cast<std::size_t>(frac * width), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%s[%s] %5.1f%%  t = %.4e s  step %ld  dt = %.3e s  ETA %s   ", label.c_str(), bar.c_str(),
                 100.0 * frac, time, step, dt, eta_text.c_str());
    std::fflush(stderr);
    return;
  }
  const int decile = static_cast<int>(frac * 10.0);
  if (decile > last_decile_ || std::chrono::duration<double>(now - last_print_).count() > 30.0) {
    last_decile_ = decile;
    last_print_ = now;
    spdlog::info("{}t = {:.4e} s ({:.0f}%), step {}, dt = {:.3e} s, wall {:.1f} s, ETA {}", label, time, 100.0 * frac,
                 step, dt, wall, eta_text);
  }
}

void Progress::finish() {
  if (enabled_ && tty_) std::fprintf(stderr, "\n");
  enabled_ = false;  // one line end, however often the run loop finishes a phase
}

}  // namespace ballista
