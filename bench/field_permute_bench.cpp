// Reordering the points' fields (FieldStore::permute): what MPM's multi-rate step does at every step
// (fast points first, then slow; mpm_multirate.cpp) and the cell sort every few steps. The store
// holds the field shapes of a geomodel point set (6 vectors, 6 tensors, 12 scalars, 3 integers:
// 696 bytes a point) and is permuted as a multi-rate partition: every fifth run of 64 points
// first, the rest after, both in order. Reports points permuted per second; bytes moved are
// read and written twice (gather into scratch, copy back).
//   build/bench/field_permute_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "core/field_store.hpp"
#include "core/parallel.hpp"

namespace {

void BM_Permute(benchmark::State& state) {
  const ballista::Index n = state.range(0);
  ballista::set_threads(static_cast<int>(state.range(1)));
  ballista::FieldStore fs;
  for (int k = 0; k < 6; ++k) fs.add_real("v" + std::to_string(k), 3, "1");
  for (int k = 0; k < 6; ++k) fs.add_real("m" + std::to_string(k), 9, "1");
  for (int k = 0; k < 12; ++k) fs.add_real("s" + std::to_string(k), 1, "1");
  for (int k = 0; k < 3; ++k) fs.add_int("i" + std::to_string(k), 1, "1");
  fs.resize(n);
  for (const auto& f : fs.fields())
    if (f.type == ballista::FieldType::Real) {
      double* d = fs.real(f.name);
      for (ballista::Index i = 0; i < n * f.ncomp; ++i) d[i] = static_cast<double>(i);
    }
  std::vector<ballista::Index> order;
  order.reserve(static_cast<std::size_t>(n));
  for (ballista::Index i = 0; i < n; ++i)
    if ((i / 64) % 5 == 0) order.push_back(i);
  for (ballista::Index i = 0; i < n; ++i)
    if ((i / 64) % 5 != 0) order.push_back(i);
  for (auto _ : state) {
    fs.permute(order);
    benchmark::ClobberMemory();
  }
  state.counters["points_per_second"] =
      benchmark::Counter(static_cast<double>(n) * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  state.counters["bytes_per_point"] = fs.bytes_per_point();
}

}  // namespace

BENCHMARK(BM_Permute)->ArgsProduct({{40000, 1000000}, {1, 2}})->UseRealTime()->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
