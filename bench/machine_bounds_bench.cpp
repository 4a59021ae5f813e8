// What this machine can do at most, the two bounds of the roofline in docs/performance.md:
// - memory bandwidth: the STREAM triad a[i] = b[i] + s c[i] (McCalpin, "Memory bandwidth and
//   machine balance in current high performance computers", IEEE TCCA Newsletter, Dec. 1995) over
//   arrays of 256 MiB each (8x the L3), 24 bytes per element as STREAM counts them (the write-
//   allocate read of a is not counted, as in STREAM);
// - floating point: fused multiply-adds on independent accumulators, 2 flops each, (a) 4-wide
//   (AVX2, what -march=native gives the vectorised loops) and (b) scalar (the Mat3 arithmetic of
//   the kernels compiles mostly to scalar FMAs), with enough accumulators to cover the FMA latency
//   on two pipes.
// On 1 and 2 threads. Throughput in bytes_per_second / flops_per_second.
//   ./build/bench/machine_bounds_bench
#include <benchmark/benchmark.h>

#include <cstddef>
#include <vector>

#include "core/parallel.hpp"

namespace {

constexpr std::size_t kStreamElements = std::size_t{1} << 25;  // 256 MiB per array

void BM_StreamTriad(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  ballista::set_threads(threads);
  const long n = static_cast<long>(kStreamElements);
  // Not std::vector's value-initialisation: first touch in parallel, each thread its own pages.
  double* a = new double[kStreamElements];
  double* b = new double[kStreamElements];
  double* c = new double[kStreamElements];
#pragma omp parallel for schedule(static)
  for (long i = 0; i < n; ++i) {
    a[i] = 0.0;
    b[i] = 1.0;
    c[i] = 2.0;
  }
  const double s = 3.0;
  for (auto _ : state) {
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) a[i] = b[i] + s * c[i];
    benchmark::DoNotOptimize(a);
    benchmark::ClobberMemory();
  }
  state.counters["threads"] = threads;
  state.counters["bytes_per_second"] = benchmark::Counter(
      24.0 * static_cast<double>(n) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  delete[] a;
  delete[] b;
  delete[] c;
}

using V4 = double __attribute__((vector_size(32)));

// 10 chains of FMAs per thread (latency 4-5 cycles x 2 pipes); the multiplier and addend keep the
// accumulators bounded. The empty asm keeps each accumulator in its own register (and the
// multiplier and addend in registers), so that the compiler neither merges nor removes the chains;
// the scalar instance is kept from being vectorised.
template <class T>
[[gnu::noinline, gnu::optimize("no-tree-vectorize", "no-tree-slp-vectorize")]] double fma_chains(long iterations,
                                                                                             double seed) {
  T a0 = T{} + seed, a1 = a0 + 1, a2 = a0 + 2, a3 = a0 + 3, a4 = a0 + 4;
  T a5 = a0 + 5, a6 = a0 + 6, a7 = a0 + 7, a8 = a0 + 8, a9 = a0 + 9;
  T m = T{} + 0.999999, add = T{} + 1e-6;
  asm volatile("" : "+x"(m), "+x"(add));
  for (long it = 0; it < iterations; ++it) {
    a0 = a0 * m + add; a1 = a1 * m + add; a2 = a2 * m + add; a3 = a3 * m + add; a4 = a4 * m + add;
    a5 = a5 * m + add; a6 = a6 * m + add; a7 = a7 * m + add; a8 = a8 * m + add; a9 = a9 * m + add;
    asm volatile("" : "+x"(a0), "+x"(a1), "+x"(a2), "+x"(a3), "+x"(a4));
    asm volatile("" : "+x"(a5), "+x"(a6), "+x"(a7), "+x"(a8), "+x"(a9));
  }
  const T total = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7 + a8 + a9;
  if constexpr (sizeof(T) == sizeof(double))
    return total;
  else
    return total[0] + total[1] + total[2] + total[3];
}

template <class T>
void BM_FmaPeak(benchmark::State& state) {
  const int threads = static_cast<int>(state.range(0));
  ballista::set_threads(threads);
  constexpr long kIterations = 20'000'000;
  constexpr double kWidth = sizeof(T) / sizeof(double);
  double sink = 0.0;
  for (auto _ : state) {
#pragma omp parallel for schedule(static) reduction(+ : sink) num_threads(threads)
    for (int t = 0; t < threads; ++t) sink += fma_chains<T>(kIterations, 1.0 + t);
  }
  benchmark::DoNotOptimize(sink);
  state.counters["threads"] = threads;
  state.counters["flops_per_second"] = benchmark::Counter(
      2.0 * 10.0 * kWidth * kIterations * threads * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}

BENCHMARK(BM_StreamTriad)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
#ifdef __AVX__  // a 4-wide accumulator fits one register only with AVX (the sanitized build has none)
BENCHMARK(BM_FmaPeak<V4>)->Name("BM_FmaPeak/avx2")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();
#endif
BENCHMARK(BM_FmaPeak<double>)->Name("BM_FmaPeak/scalar")->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
