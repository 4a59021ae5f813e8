// Cost of a checkpoint (issue 16, docs/restart.md): the 3D J2 block of mpm_block_impact_bench at
// 1e5 and 1e6 particles after a few steps; times save_state + write_checkpoint_file (HDF5, fsync,
// rename) and read_checkpoint_file + load_state, and reports bytes per particle and MB/s, so that
// a checkpoint interval can be chosen against the cost of a step (docs/performance.md).
//   ./build/bench/checkpoint_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <unistd.h>

#include "block_impact_deck.hpp"
#include "core/parallel.hpp"
#include "core/state_archive.hpp"
#include "deck/deck_reader.hpp"
#include "io/checkpoint_file.hpp"
#include "run/simulation.hpp"

namespace {

std::string scratch_dir() {
  return (std::filesystem::temp_directory_path() / ("ballista_checkpoint_bench_" + std::to_string(::getpid())))
      .string();
}

void BM_Checkpoint(benchmark::State& state, bool write) {
  ballista::set_threads(2);
  const ballista::Scenario sc = ballista::parse_deck(ballista::bench::block_impact_deck(state.range(0), "linear"), "bench.yaml");
  auto solver = ballista::make_solver(sc);
  for (int k = 0; k < 3; ++k) solver->step(solver->stable_dt());
  const std::string dir = scratch_dir();
  const std::string path = ballista::checkpoint_path(dir, solver->steps());
  {
    ballista::StateArchive a;
    solver->save_state(a);
    ballista::write_checkpoint_file(path, a);
  }
  for (auto _ : state) {
    if (write) {
      ballista::StateArchive a;
      solver->save_state(a);
      ballista::write_checkpoint_file(path, a);
    } else {
      solver->load_state(ballista::read_checkpoint_file(path));
    }
  }
  const double bytes = static_cast<double>(std::filesystem::file_size(path));
  const double n = static_cast<double>(solver->points().size());
  state.counters["particles"] = n;
  state.counters["bytes_per_particle"] = bytes / n;
  state.counters["MB_per_second"] =
      benchmark::Counter(bytes * 1e-6 * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  std::filesystem::remove_all(dir);
}

}  // namespace

BENCHMARK_CAPTURE(BM_Checkpoint, write, true)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK_CAPTURE(BM_Checkpoint, read, false)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond)->UseRealTime();

BENCHMARK_MAIN();
