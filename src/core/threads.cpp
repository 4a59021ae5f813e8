#include "core/threads.hpp"

#include <thread>

#include <spdlog/spdlog.h>

#include "core/parallel.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ballista {

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

}  // namespace ballista
