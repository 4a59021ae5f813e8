#include "core/threads.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <thread>

#include <spdlog/spdlog.h>

#include "core/parallel.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ballista {

namespace {
/// Set in the environment of the re-executed image: never re-execute twice.
constexpr const char* kReexecGuard = "BALLISTA_OMP_REEXEC";
}  // namespace

int available_cores() {
#ifdef _OPENMP
  const int n = omp_get_num_procs();
#else
  const int n = static_cast<int>(std::thread::hardware_concurrency());
#endif
  return n > 0 ? n : 1;
}

int clamp_thread_count(int requested, int cores) {
  if (requested <= 0) return requested;
  return requested > cores ? (cores > 0 ? cores : 1) : requested;
}

int request_threads(int n, const char* source) {
  if (n <= 0) return max_threads();
  const int cores = available_cores();
  const int used = clamp_thread_count(n, cores);
  if (used != n)
    spdlog::warn("{} = {} is more than the {} cores available: using {} threads", source, n, cores, used);
  set_threads(used);
  return max_threads();
}

void ensure_omp_wait_policy(char** argv) {
  if (std::getenv(kReexecGuard)) {
    unsetenv(kReexecGuard);  // keep it out of the environment of the processes we start
    return;
  }
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;  // the user's choice
  if (setenv(kOmpWaitDefault.name, kOmpWaitDefault.value, 1) != 0 || setenv(kReexecGuard, "1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  const int err = errno;
  unsetenv(kReexecGuard);
  spdlog::warn("could not re-execute with {}={} ({}): OpenMP threads spin while they wait, which is slow when "
               "other processes share the cores; set {} yourself",
               kOmpWaitDefault.name, kOmpWaitDefault.value, std::strerror(err), kOmpWaitDefault.name);
}

}  // namespace ballista
