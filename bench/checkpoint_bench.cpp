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

#include "core/parallel.hpp"
#include "core/state_archive.hpp"
#include "io/checkpoint_file.hpp"
#include "io/deck_reader.hpp"
#include "run/simulation.hpp"

namespace {

std::string deck(long particles) {
  // As bench/mpm_block_impact_bench.cpp: 8 particles per cell, block nx x 0.8 nx x nx cells.
  const double cells = static_cast<double>(particles) / 8.0;
  const int nx = static_cast<int>(std::lround(std::cbrt(cells / 0.8)));
  const int ny = static_cast<int>(std::lround(0.8 * nx));
  const double h = 1.0e-3, lx = nx * h, ly = ny * h, m = 4 * h;
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
simulation: {solver: mpm, dimension: 3d, end_time: 1.0, cfl: 0.3, on_particle_exit: delete}
materials:
  steel: {model: j2_plasticity, density: 7850, youngs_modulus: 200.0e9, poisson_ratio: 0.29,
          yield_stress: 350.0e6, hardening_modulus: 1.0e9}
mpm: {shape_function: linear, update: musl, flip: 0.99}
grid: {lower: [0, 0, 0], upper: [%g, %g, %g], cell_size: %g, boundary: {y_min: wall}}
bodies:
  - {name: block, material: steel, particles_per_cell: 2, velocity: [0, -200.0, 0],
     shape: {type: box, lower: [%g, %g, %g], upper: [%g, %g, %g]}}
)",
                lx + 2 * m, ly + 2 * h, lx + 2 * m, h, m, 0.0, m, m + lx, ly, m + lx);
  return buf;
}

std::string scratch_dir() {
  return (std::filesystem::temp_directory_path() / ("ballista_checkpoint_bench_" + std::to_string(::getpid())))
      .string();
}

void BM_Checkpoint(benchmark::State& state, bool write) {
  ballista::set_threads(2);
  const ballista::Scenario sc = ballista::parse_deck(deck(state.range(0)), "bench.yaml");
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
