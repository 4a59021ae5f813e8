// Parallel loops: results must not depend on the thread count (core/parallel.hpp promise).
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "core/parallel.hpp"

namespace test_parallel {

using namespace ballista;

namespace {

// Restores the thread count a test changed.
struct ThreadGuard {
  int saved = max_threads();
  ~ThreadGuard() { set_threads(saved); }
};

// Reference: the documented reduction order (fixed chunks of kReduceChunk summed serially, chunk
// partials combined in chunk order), written out serially.
template <int N>
void reference_sum(const std::vector<double>& a, Index begin, Index end, double (&out)[N]) {
  for (int k = 0; k < N; ++k) out[k] = 0.0;
  for (Index lo = begin; lo < end; lo += kReduceChunk) {
    double local[N] = {};
    const Index hi = std::min(lo + kReduceChunk, end);
    for (Index i = lo; i < hi; ++i)
      for (int k = 0; k < N; ++k) local[k] += a[i] * (k + 1) + (k == 2 ? a[i] * a[i] : 0.0);
    for (int k = 0; k < N; ++k) out[k] += local[k];
  }
}

bool bitwise_equal(double a, double b) { return std::memcmp(&a, &b, sizeof(double)) == 0; }

}  // namespace

TEST(Parallel, DeterministicSumIsBitwiseIndependentOfThreadCount) {
  ThreadGuard guard;
  // Values spanning 12 orders of magnitude with both signs: a naive parallel sum would differ
  // from the serial one in the last bits, so bitwise equality is a real check of the order.
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> mant(-1.0, 1.0);
  std::uniform_int_distribution<int> expo(-6, 6);
  const Index n = 23 * kReduceChunk + 517;  // many chunks, last one partial
  std::vector<double> a(n);
  for (auto& x : a) x = mant(rng) * std::pow(10.0, expo(rng));
  auto value = [&](Index i, double* o) {
    o[0] += a[i];
    o[1] += 2.0 * a[i];
    o[2] += 3.0 * a[i] + a[i] * a[i];
  };
  for (Index begin : {Index(0), Index(1000)}) {
    double ref[3], one[3], two[3];
    reference_sum<3>(a, begin, n, ref);
    set_threads(1);
    deterministic_sum<3>(begin, n, value, one);
    set_threads(2);
    deterministic_sum<3>(begin, n, value, two);
    for (int k = 0; k < 3; ++k) {
      EXPECT_TRUE(bitwise_equal(one[k], two[k])) << k << ": " << one[k] << " vs " << two[k];
      EXPECT_TRUE(bitwise_equal(one[k], ref[k])) << k << ": " << one[k] << " vs " << ref[k];
    }
  }
}

TEST(Parallel, DeterministicSumOfEmptyRangeIsZero) {
  double out[2] = {5.0, 6.0};
  deterministic_sum<2>(10, 10, [](Index, double* o) { o[0] += 1.0; o[1] += 1.0; }, out);
  EXPECT_EQ(out[0], 0.0);
  EXPECT_EQ(out[1], 0.0);
  deterministic_sum<2>(10, 3, [](Index, double* o) { o[0] += 1.0; }, out);
  EXPECT_EQ(out[0], 0.0);
}

TEST(Parallel, DeterministicSumCountsEveryIndexOnce) {
  ThreadGuard guard;
  set_threads(2);
  // Exact in floating point (integers < 2^53): sum of i over [b, e) and the count.
  const Index b = 7, e = 5 * kReduceChunk + 3;
  double out[2];
  deterministic_sum<2>(b, e, [](Index i, double* o) { o[0] += 1.0; o[1] += static_cast<double>(i); }, out);
  EXPECT_EQ(out[0], static_cast<double>(e - b));
  EXPECT_EQ(out[1], 0.5 * static_cast<double>(e - 1 + b) * static_cast<double>(e - b));
}

TEST(Parallel, ForEachVisitsEveryIndexExactlyOnce) {
  ThreadGuard guard;
  set_threads(2);
  for (Index n : {Index(10), Index(4 * kParallelThreshold + 3)}) {
    std::vector<int> hits(n + 5, 0);
    for_each(5, n + 5, [&](Index i) { hits[i] += 1; });
    for (Index i = 0; i < 5; ++i) EXPECT_EQ(hits[i], 0);
    for (Index i = 5; i < n + 5; ++i) ASSERT_EQ(hits[i], 1) << i;
  }
}

TEST(Parallel, UnevenLocalVisitsEveryIndexExactlyOnce) {
  ThreadGuard guard;
  // Below the threshold (serial), one chunk, a partial last chunk, more chunks than threads, and
  // an uneven cost (the first eighth of the indices 200 times dearer), so that a thread finishes
  // its own run early and takes chunks from the other's.
  for (int threads : {1, 2, 3}) {
    set_threads(threads);
    for (Index n : {Index(10), Index(kPointChunk), Index(23 * kPointChunk + 17), Index(40 * kPointChunk)}) {
      std::vector<std::atomic<int>> hits(n + 3);
      for (auto& h : hits) h.store(0);
      std::vector<double> sink(n + 3, 0.0);
      for_each_uneven_local(3, n + 3, 8, kPointChunk, [&](Index i) {
        double x = 1.0;
        const int work = i < 3 + n / 8 ? 200 : 1;
        for (int k = 0; k < work; ++k) x = std::sqrt(x + static_cast<double>(k));
        sink[i] = x;
        hits[i].fetch_add(1);
      });
      for (Index i = 0; i < 3; ++i) EXPECT_EQ(hits[i].load(), 0);
      for (Index i = 3; i < n + 3; ++i) ASSERT_EQ(hits[i].load(), 1) << "threads " << threads << " n " << n << " i " << i;
    }
  }
}

#ifdef _OPENMP
TEST(Parallel, PointChunksFollowOpenMpStaticSplit) {
  // for_each_uneven_local starts each thread on the run OpenMP's static schedule gives it in
  // for_each_point_chunk, so that the passes of a step keep each point on one core.
  ThreadGuard guard;
  for (int threads : {2, 3}) {
    set_threads(threads);
    for (Index nchunk : {Index(2), Index(3), Index(23), Index(64)}) {
      std::vector<int> owner(nchunk, -1);
      for_each_point_chunk(nchunk, [&](Index c) { owner[c] = omp_get_thread_num(); });
      for (int r = 0; r < threads; ++r)
        for (Index c = static_run_begin(nchunk, threads, r); c < static_run_begin(nchunk, threads, r + 1); ++c)
          EXPECT_EQ(owner[c], r) << "threads " << threads << " chunks " << nchunk << " chunk " << c;
      EXPECT_EQ(static_run_begin(nchunk, threads, threads), nchunk);
    }
  }
}
#endif

#ifdef _OPENMP
TEST(Parallel, SetThreadsChangesMaxThreads) {
  ThreadGuard guard;
  set_threads(2);
  EXPECT_EQ(max_threads(), 2);
  set_threads(0);  // 0 = leave unchanged
  EXPECT_EQ(max_threads(), 2);
  set_threads(1);
  EXPECT_EQ(max_threads(), 1);
}
#endif

}  // namespace test_parallel
