#pragma once
// Thread-count requests. The loops themselves are in core/parallel.hpp.

namespace ballista {

/// Processors this process may run on: omp_get_num_procs() (honours the CPU affinity mask), else
/// std::thread::hardware_concurrency(); at least 1.
int available_cores();

/// The thread count used for a request of `requested` threads on `cores` cores: requests above
/// the cores are clamped to them (more threads than cores only wait for each other); 0 and
/// negative requests are returned unchanged (0 = the default: all cores).
int clamp_thread_count(int requested, int cores);

/// Applies a user's thread request (`--threads`, `simulation.threads`; `source` names it in the
/// warning): n <= 0 leaves the OpenMP default; n above available_cores() is clamped with a
/// spdlog warning naming both numbers. Returns the thread count in effect afterwards.
int request_threads(int n, const char* source);

}  // namespace ballista
