#pragma once
// Wall-clock seconds accumulated per phase of a solver step, for the per-phase split of the
// benchmarks (docs/performance.md). Two clock reads per phase and step: negligible next to any
// phase. Timings never feed back into the computation, so results stay deterministic.
#include <chrono>

namespace ballista {

/// Seconds since t0.
inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

/// Adds the seconds between its construction and destruction to `sink`.
class ScopedPhase {
 public:
  explicit ScopedPhase(double& sink) : sink_(sink), start_(std::chrono::steady_clock::now()) {}
  ~ScopedPhase() { sink_ += seconds_since(start_); }
  ScopedPhase(const ScopedPhase&) = delete;
  ScopedPhase& operator=(const ScopedPhase&) = delete;

 private:
  double& sink_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace ballista
