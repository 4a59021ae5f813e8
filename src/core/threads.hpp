#pragma once
// Thread-count requests and the OpenMP wait policy of the `ballista` program (docs/performance.md,
// "Busy cores"). The loops themselves are in core/parallel.hpp.

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

/// The wait policy `ballista` runs with when the user sets neither OMP_WAIT_POLICY nor
/// GOMP_SPINCOUNT: `name`=`value` is put in the environment. Chosen by measurement
/// (docs/performance.md): spinning threads make a 2-thread run many times slower than 1 thread
/// when another process occupies a core.
struct OmpWaitDefault {
  const char* name;
  const char* value;
};
inline constexpr OmpWaitDefault kOmpWaitDefault{"OMP_WAIT_POLICY", "passive"};

/// Call first thing in main(). libgomp reads its environment in a shared-library constructor,
/// before main(), so setting the variable here is too late for this process image: when neither
/// OMP_WAIT_POLICY nor GOMP_SPINCOUNT is set, this sets kOmpWaitDefault and re-executes the program
/// (/proc/self/exe, same argv and environment plus the variable; a guard variable prevents a
/// second re-exec). Returns when nothing needs doing, or if the re-exec failed (then with a
/// warning: this process keeps libgomp's default, processes it starts get the variable).
void ensure_omp_wait_policy(char** argv);

}  // namespace ballista
