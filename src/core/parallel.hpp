#pragma once
// Parallel loops over index ranges. Maps to OpenMP today. Results never depend on the thread
// count: loops write disjoint data, and reductions sum fixed-size chunks whose partial results
// are combined in chunk order (see deterministic_sum).
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "core/threads.hpp"  // request_threads: a user's thread count, clamped to the cores

#ifdef _OPENMP
#include <omp.h>
#endif

namespace ballista {

using Index = std::int64_t;

inline int max_threads() {
#ifdef _OPENMP
  return omp_get_max_threads();
#else
  return 1;
#endif
}
/// Sets the OpenMP thread count exactly (n <= 0: unchanged), also above the cores (tests use it to
/// compare thread counts); user requests go through request_threads.
inline void set_threads(int n) {
#ifdef _OPENMP
  if (n > 0) omp_set_num_threads(n);
#else
  (void)n;
#endif
}

/// Below this many iterations a loop runs on the calling thread: starting a parallel region
/// costs more than the work (and oversubscribed machines make spinning threads expensive).
inline constexpr Index kParallelThreshold = 4096;

/// Calls f(i) for i in [begin, end); iterations must write disjoint data.
template <class F>
inline void for_each(Index begin, Index end, F&& f) {
#pragma omp parallel for schedule(static) if (end - begin > kParallelThreshold)
  for (Index i = begin; i < end; ++i) f(i);
}

/// For loops whose iterations each cost microseconds (an LME solve, a gather over dozens of
/// support entries): a parallel region pays for itself from a few hundred iterations, and the
/// dynamic schedule evens out iterations of uneven cost (supports of 8 to 300 nodes).
inline constexpr Index kHeavyParallelThreshold = 256;

/// for_each for heavy iterations (see kHeavyParallelThreshold); iterations must write disjoint data.
template <class F>
inline void for_each_heavy(Index begin, Index end, F&& f) {
#pragma omp parallel for schedule(dynamic, 16) if (end - begin > kHeavyParallelThreshold)
  for (Index i = begin; i < end; ++i) f(i);
}

/// Calls f(c) for c in [0, nchunk): each c a chunk of thousands of iterations (a fixed cut, so
/// results do not depend on the thread count), in parallel whenever there are two, handed out one
/// at a time (chunks cost unevenly). for_each would run fewer than kParallelThreshold chunks on
/// one thread.
template <class F>
inline void for_each_chunk(Index nchunk, F&& f) {
#pragma omp parallel for schedule(dynamic, 1) if (nchunk > 1)
  for (Index c = 0; c < nchunk; ++c) f(c);
}

/// The chunk of the point passes' common split (for_each_point_chunk, for_each_uneven_local):
/// each thread takes one contiguous run of such chunks, the same run in every pass of a step, so
/// that a pass finds on each core the points that core wrote in the pass before. Handed out one at
/// a time instead, the chunks of a 10^4-point step moved between the cores' caches at every pass
/// (docs/performance.md, "One split of the points").
inline constexpr Index kPointChunk = 512;

/// First chunk of thread r's run when `nchunk` chunks are split over `threads`: OpenMP's static
/// schedule as libgomp cuts it (the first nchunk % threads threads take one chunk more).
inline Index static_run_begin(Index nchunk, int threads, int r) {
  const Index q = nchunk / threads, rem = nchunk % threads;
  return r * q + (r < rem ? r : rem);
}

/// for_each_chunk for chunks of kPointChunk consecutive points that cost alike: each thread takes
/// its run of the common split, the same at every call with the same count.
template <class F>
inline void for_each_point_chunk(Index nchunk, F&& f) {
#pragma omp parallel for schedule(static) if (nchunk > 1)
  for (Index c = 0; c < nchunk; ++c) f(c);
}

/// A pass over points whose cost clusters (a material update: the yielding points of a crater sit
/// together, points being sorted by cell) that keeps the common split (kPointChunk, when `chunk`
/// iterations are kPointChunk points; serial up to `threshold` iterations): thread t first takes
/// its own run of chunks, in order, then helps with the chunks the others have not yet taken.
/// Which thread runs a chunk never changes what it computes.
template <class F>
inline void for_each_uneven_local(Index begin, Index end, Index threshold, Index chunk, F&& f) {
  const Index n = end - begin;
  const int threads = max_threads();
  if (n <= threshold || threads < 2) {
    for (Index i = begin; i < end; ++i) f(i);
    return;
  }
  const Index nchunk = (n + chunk - 1) / chunk;
  struct alignas(64) Cursor {
    std::atomic<Index> next;
  };
  const std::unique_ptr<Cursor[]> cursor(new Cursor[threads]);
  for (int r = 0; r < threads; ++r) cursor[r].next.store(static_run_begin(nchunk, threads, r), std::memory_order_relaxed);
#pragma omp parallel num_threads(threads)
  {
#ifdef _OPENMP
    const int t = omp_get_thread_num();
#else
    const int t = 0;
#endif
    for (int k = 0; k < threads; ++k) {
      const int r = (t + k) % threads;
      const Index stop = static_run_begin(nchunk, threads, r + 1);
      for (Index c = cursor[r].next.fetch_add(1, std::memory_order_relaxed); c < stop;
           c = cursor[r].next.fetch_add(1, std::memory_order_relaxed)) {
        const Index lo = begin + c * chunk;
        const Index hi = lo + chunk < end ? lo + chunk : end;
        for (Index i = lo; i < hi; ++i) f(i);
      }
    }
  }
}

/// for_each for loops whose cheap iterations cost unevenly by index (a peridynamic step: the
/// gas points, stored after the case's, carry the gas pairs too): a static split would leave one
/// thread with most of the work.
template <class F>
inline void for_each_uneven(Index begin, Index end, F&& f) {
#pragma omp parallel for schedule(dynamic, 512) if (end - begin > kParallelThreshold)
  for (Index i = begin; i < end; ++i) f(i);
}

/// Chunk size for reductions: fixed, so chunk boundaries (and thus round-off) do not depend on
/// the number of threads.
inline constexpr Index kReduceChunk = 4096;

/// Sums N values per index, value(i, out[N]) adding into out; bitwise reproducible for any
/// thread count because chunk partials are combined serially in chunk order.
template <int N, class F>
inline void deterministic_sum(Index begin, Index end, F&& value, double (&result)[N]) {
  for (int k = 0; k < N; ++k) result[k] = 0.0;
  if (end <= begin) return;
  const Index nchunk = (end - begin + kReduceChunk - 1) / kReduceChunk;
  std::vector<double> partial(static_cast<size_t>(nchunk) * N, 0.0);
#pragma omp parallel for schedule(static) if (nchunk > 1)
  for (Index c = 0; c < nchunk; ++c) {
    double local[N] = {};
    const Index lo = begin + c * kReduceChunk;
    const Index hi = lo + kReduceChunk < end ? lo + kReduceChunk : end;
    for (Index i = lo; i < hi; ++i) value(i, local);
    for (int k = 0; k < N; ++k) partial[c * N + k] = local[k];
  }
  for (Index c = 0; c < nchunk; ++c)
    for (int k = 0; k < N; ++k) result[k] += partial[c * N + k];
}

}  // namespace ballista
